// embree_tracer.cpp: Embree 3 scene build and rtcIntersect1 / rtcOccluded1 tracing over
// std::threads (chunks handed out through an atomic counter). Without MONTECL_HAVE_EMBREE every
// call throws, and available() is false.
#include "bench/embree_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "bench/ray_sets.h"
#include "util/errors.h"
#include "util/parallel_for.h"

#ifdef MONTECL_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

namespace montecl {

#ifdef MONTECL_HAVE_EMBREE

namespace {

// The cut-out geometry's user data: its triangles' input indices and the test.
struct AlphaFilter {
  std::vector<std::uint32_t> inputIndex;  // primID -> input triangle
  EmbreeTracer::AlphaTest test;
};

// Intersection and occlusion filter of the cut-out geometry: rejects hits whose alpha fails.
void alphaFilter(const RTCFilterFunctionNArguments* args) {
  const auto* f = static_cast<const AlphaFilter*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    const float3 org(RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
                     RTCRayN_org_z(args->ray, args->N, i));
    const float3 dir(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                     RTCRayN_dir_z(args->ray, args->N, i));
    if (!f->test(f->inputIndex[prim], RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i), org, dir))
      args->valid[i] = 0;
  }
}

void attachTriangles(RTCDevice device, RTCScene scene, const std::vector<SceneTriangle>& all,
                     const std::vector<std::uint32_t>& pick, AlphaFilter* filter) {
  std::vector<SceneTriangle> tris;
  for (std::uint32_t i : pick) tris.push_back(all[i]);
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * tris.size()));
  auto* idx = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris.size()));
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      v[9 * i + 3 * k + 0] = tris[i].v[k].x;
      v[9 * i + 3 * k + 1] = tris[i].v[k].y;
      v[9 * i + 3 * k + 2] = tris[i].v[k].z;
      idx[3 * i + k] = unsigned(3 * i + k);
    }
  if (filter) {
    rtcSetGeometryUserData(g, filter);
    rtcSetGeometryIntersectFilterFunction(g, alphaFilter);
    rtcSetGeometryOccludedFilterFunction(g, alphaFilter);
  }
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
}

RTCScene buildScene(RTCDevice device, const std::vector<SceneTriangle>& tris, AlphaFilter* filter,
                    const std::vector<std::uint8_t>& alphaTested) {
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  std::vector<std::uint32_t> opaque, cutout;
  for (std::uint32_t i = 0; i < tris.size(); ++i)
    (filter && i < alphaTested.size() && alphaTested[i] ? cutout : opaque).push_back(i);
  if (!opaque.empty()) attachTriangles(device, scene, tris, opaque, nullptr);
  if (!cutout.empty()) {
    filter->inputIndex = cutout;
    attachTriangles(device, scene, tris, cutout, filter);
  }
  return scene;
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

struct EmbreeTracer::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  AlphaFilter filter;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

EmbreeTracer::EmbreeTracer(const std::vector<SceneTriangle>& tris, unsigned threads, AlphaTest alphaTest,
                           const std::vector<std::uint8_t>& alphaTested)
    : impl_(new Impl), threads_(std::max(1u, threads)) {
  impl_->filter.test = std::move(alphaTest);
  AlphaFilter* filter = impl_->filter.test ? &impl_->filter : nullptr;
  std::string config = "threads=" + std::to_string(threads_);
  impl_->device = rtcNewDevice(config.c_str());
  if (!impl_->device) throw RuntimeError("Embree: rtcNewDevice failed (error " +
                                         std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  for (int pass = 0; pass < 2; ++pass) {  // pass 0 warms up the thread pool and allocator
    if (impl_->scene) rtcReleaseScene(impl_->scene);
    impl_->scene = buildScene(impl_->device, tris, filter, alphaTested);
    auto t0 = std::chrono::steady_clock::now();
    rtcCommitScene(impl_->scene);
    buildMs_ = msSince(t0);
  }
  if (rtcGetDeviceError(impl_->device) != RTC_ERROR_NONE) throw RuntimeError("Embree: scene build failed");
}

EmbreeTracer::~EmbreeTracer() = default;

bool EmbreeTracer::available() { return true; }

std::string EmbreeTracer::version() {
  return std::to_string(RTC_VERSION_MAJOR) + "." + std::to_string(RTC_VERSION_MINOR) + "." +
         std::to_string(RTC_VERSION_PATCH);
}

namespace {

// montecl's Ray (origin, dir with dir.w = tmax) as an Embree ray from t = 0.
RTCRay toEmbreeRay(const Ray& r) {
  RTCRay ray;
  ray.org_x = r.origin.x; ray.org_y = r.origin.y; ray.org_z = r.origin.z;
  ray.dir_x = r.dir.x; ray.dir_y = r.dir.y; ray.dir_z = r.dir.z;
  ray.tnear = 0.0f;
  ray.tfar = r.dir.w;
  ray.time = 0.0f;
  ray.mask = ~0u;
  ray.id = 0;
  ray.flags = 0;
  return ray;
}

}  // namespace

double EmbreeTracer::closest(const std::vector<Ray>& rays, std::vector<float>& t) const {
  t.assign(rays.size(), INFINITY);
  RTCScene scene = impl_->scene;
  auto t0 = std::chrono::steady_clock::now();
  parallelChunks(rays.size(), threads_, kRayGrain, [&](std::size_t, std::size_t b, std::size_t e) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (std::size_t i = b; i < e; ++i) {
      RTCRayHit rh;
      rh.ray = toEmbreeRay(rays[i]);
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &ctx, &rh);
      if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) t[i] = rh.ray.tfar;
    }
  }, kRayGrain);
  return msSince(t0);
}

double EmbreeTracer::occluded(const std::vector<Ray>& rays, std::vector<std::uint8_t>& occ) const {
  occ.assign(rays.size(), 0);
  RTCScene scene = impl_->scene;
  auto t0 = std::chrono::steady_clock::now();
  parallelChunks(rays.size(), threads_, kRayGrain, [&](std::size_t, std::size_t b, std::size_t e) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (std::size_t i = b; i < e; ++i) {
      RTCRay ray = toEmbreeRay(rays[i]);
      rtcOccluded1(scene, &ctx, &ray);
      occ[i] = ray.tfar == -INFINITY ? 1 : 0;
    }
  }, kRayGrain);
  return msSince(t0);
}

#else  // no Embree

struct EmbreeTracer::Impl {};
EmbreeTracer::EmbreeTracer(const std::vector<SceneTriangle>&, unsigned threads, AlphaTest,
                           const std::vector<std::uint8_t>&)
    : threads_(threads) {
  throw RuntimeError("montecl was built without Embree (install libembree-dev and reconfigure)");
}
EmbreeTracer::~EmbreeTracer() = default;
bool EmbreeTracer::available() { return false; }
std::string EmbreeTracer::version() { return ""; }

double EmbreeTracer::closest(const std::vector<Ray>&, std::vector<float>&) const { return 0.0; }
double EmbreeTracer::occluded(const std::vector<Ray>&, std::vector<std::uint8_t>&) const { return 0.0; }

#endif

}  // namespace montecl
