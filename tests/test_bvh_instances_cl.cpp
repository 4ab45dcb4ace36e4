// test_bvh_instances_cl.cpp: the two-level traversal (kernels/shared/traverse_instances.h) built
// as OpenCL C on the device gives the host reference's hits bit for bit (t, slot, barycentrics,
// instance, any hit), and the device sees the Instance layout the host writes.
#include <doctest/doctest.h>

#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "bvh/bvh_instances.h"
#include "cl/devices.h"
#include "cl/kernel_source.h"
#include "cl/opencl.h"
#include "cl/program_cache.h"
#include "cli_runner.h"
#include "soups.h"

namespace test_file_bvh_instances_cl {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using glm::vec3;
using montecl_test::TempDir;

namespace {
// Sets (or, with nullptr, unsets) an environment variable for a scope.
struct ScopedEnv {
  std::string name, old;
  bool had = false;
  ScopedEnv(const char* n, const char* value) : name(n) {
    if (const char* v = std::getenv(n)) had = true, old = v;
    if (value)
      ::setenv(n, value, 1);
    else
      ::unsetenv(n);
  }
  ~ScopedEnv() {
    if (had)
      ::setenv(name.c_str(), old.c_str(), 1);
    else
      ::unsetenv(name.c_str());
  }
};
}  // namespace

TEST_CASE("bvh instances: the device's two-level traversal is the host's bit for bit" * doctest::test_suite("opencl")) {
  TempDir dir;
  ScopedEnv cache("MONTECL_CACHE_DIR", dir.path.c_str());
  ScopedEnv kdir("MONTECL_KERNEL_DIR", nullptr);  // the embedded (real) headers
  std::vector<std::vector<SceneTriangle>> meshes = {montecl_test::seededSoup(200, 41, 3.0f, 1.0f, 0.2f),
                                                    montecl_test::seededSoup(80, 42, 5.0f, 2.0f, 0.5f)};
  std::vector<BvhInstanceDesc> inst;
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int k = 0; k < 40; ++k) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), (vec3(u(rng), u(rng), u(rng)) - 0.5f) * 40.0f);
    m = glm::rotate(m, 6.2831853f * u(rng), glm::normalize(vec3(u(rng), u(rng), u(rng)) + 0.1f));
    m = glm::scale(m, vec3(0.5f + u(rng), (k % 5 == 0 ? -1.0f : 1.0f) * (0.5f + u(rng)), 0.5f + u(rng)));
    inst.push_back({std::uint32_t(k % 2), m});
  }
  const TwoLevelBvh bvh = buildTwoLevelBvh(meshes, inst);
  std::vector<Ray> rays(4000);
  for (Ray& r : rays) {
    const vec3 o = (vec3(u(rng), u(rng), u(rng)) - 0.5f) * 60.0f;
    const vec3 d = glm::normalize((vec3(u(rng), u(rng), u(rng)) - 0.5f) * 30.0f - o);
    r.origin = glm::vec4(o, 0.0f);
    r.dir = glm::vec4(d, u(rng) < 0.5f ? INFINITY : 70.0f * u(rng));
  }
  const std::string src = expandedKernelSource("shared/traverse_instances.h") + R"(
__kernel void trace(__global const WideNode* nodes, __global const Triangle* tris, __global const Instance* inst,
                    __global const Ray* rays, __global Hit* hits, __global uint* hitInst, __global int* any) {
  uint i = get_global_id(0);
  Ray r = rays[i];
  InstanceHit h = instances_closest_hit(nodes, tris, inst, 0, xyz(r.origin), xyz(r.dir), r.dir.w);
  hits[i] = h.hit;
  hitInst[i] = h.instance == MCL_NO_INSTANCE ? MCL_NO_INSTANCE : inst[h.instance].id;
  any[i] = instances_any_hit(nodes, tris, inst, 0, xyz(r.origin), xyz(r.dir), r.dir.w);
}
__kernel void layout(__global uint* out) {
  out[0] = sizeof(Instance);
  out[1] = (uint)__builtin_offsetof(Instance, objectToWorld);
  out[2] = (uint)__builtin_offsetof(Instance, root);
  out[3] = (uint)__builtin_offsetof(Instance, id);
}
)";
  DeviceInfo dev = selectDevice("");
  cl::Context context(dev.device);
  ProgramBuild build = buildProgramCached(context, dev, src, "-cl-std=CL1.2");
  cl::CommandQueue queue(context, dev.device);
  auto upload = [&](const auto& v) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    return cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, v.size() * sizeof(T), const_cast<T*>(v.data()));
  };
  cl::Buffer nodes = upload(bvh.nodes), tris = upload(bvh.triangles), insts = upload(bvh.instances), rb = upload(rays);
  cl::Buffer hits(context, CL_MEM_WRITE_ONLY, rays.size() * sizeof(Hit));
  cl::Buffer hitInst(context, CL_MEM_WRITE_ONLY, rays.size() * sizeof(cl_uint));
  cl::Buffer any(context, CL_MEM_WRITE_ONLY, rays.size() * sizeof(cl_int));
  cl::Buffer lay(context, CL_MEM_WRITE_ONLY, 4 * sizeof(cl_uint));
  cl::Kernel k(build.program, "trace");
  k.setArg(0, nodes);
  k.setArg(1, tris);
  k.setArg(2, insts);
  k.setArg(3, rb);
  k.setArg(4, hits);
  k.setArg(5, hitInst);
  k.setArg(6, any);
  queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(rays.size()));
  cl::Kernel kl(build.program, "layout");
  kl.setArg(0, lay);
  queue.enqueueNDRangeKernel(kl, cl::NullRange, cl::NDRange(1));
  std::vector<Hit> dh(rays.size());
  std::vector<cl_uint> di(rays.size()), dl(4);
  std::vector<cl_int> da(rays.size());
  queue.enqueueReadBuffer(hits, CL_TRUE, 0, dh.size() * sizeof(Hit), dh.data());
  queue.enqueueReadBuffer(hitInst, CL_TRUE, 0, di.size() * sizeof(cl_uint), di.data());
  queue.enqueueReadBuffer(any, CL_TRUE, 0, da.size() * sizeof(cl_int), da.data());
  queue.enqueueReadBuffer(lay, CL_TRUE, 0, dl.size() * sizeof(cl_uint), dl.data());
  CHECK(dl[0] == sizeof(Instance));
  CHECK(dl[1] == offsetof(Instance, objectToWorld));
  CHECK(dl[2] == offsetof(Instance, root));
  CHECK(dl[3] == offsetof(Instance, id));
  int hitCount = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const TwoLevelHit h = intersectClosest(bvh, vec3(rays[i].origin), vec3(rays[i].dir), rays[i].dir.w);
    CAPTURE(i);
    CHECK(as_uint(dh[i].t) == as_uint(h.hit.t));
    CHECK(dh[i].tri == h.hit.tri);
    CHECK(as_uint(dh[i].u) == as_uint(h.hit.u));
    CHECK(as_uint(dh[i].v) == as_uint(h.hit.v));
    CHECK(di[i] == h.instance);
    CHECK((da[i] != 0) == intersectAny(bvh, vec3(rays[i].origin), vec3(rays[i].dir), rays[i].dir.w));
    hitCount += h.hit.tri != MCL_NO_HIT;
  }
  MESSAGE(hitCount << " of " << rays.size() << " rays hit on " << dev.name);
  CHECK(hitCount > 400);
}

}  // namespace test_file_bvh_instances_cl
