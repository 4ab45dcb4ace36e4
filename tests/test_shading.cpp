// test_shading.cpp: per-triangle surface attributes and shading normals (the below-surface rule): the device
// attribute buffer in BVH order (render/triangle_shading.h), the pure shading-normal rule
// (kernels/shared/shading.h), and renders through the kernels: the N AOV of a low-poly sphere with
// and without normals, AO exactly 1 on a smooth sphere in open space (no dark rings), direct light
// from a polygon under a tilted shading normal against the form factor, no light through a surface;
// and end to end: an OBJ sphere with `vn` through `montecl render --aov normal`.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "image/exr_layers.h"
#include "film_stats.h"
#include "kernels/shared/rng.h"
#include "kernels/shared/surface_texture.h"
#include "kernels/shared/shading.h"
#include "kernels/stages/stage_common.h"
#include "render/frame_params.h"
#include "render/triangle_shading.h"
#include "render/wavefront.h"
#include "skip.h"
#include "soups.h"
#include "stats.h"
#include "test_scenes.h"

namespace test_file_shading {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

TEST_CASE("shading buffer: BVH order, flags in e2.w, a 1-entry dummy without attributes" * doctest::test_suite("cpu")) {
  std::vector<SceneTriangle> tris = seededSoup(200, 7, 2.0f, 0.5f, 0.1f);
  Bvh plain = buildBvh(tris);
  CHECK(buildTriangleShading(tris, plain).size() == 1);
  for (const Triangle& t : plain.triangles) CHECK(as_uint(t.e2.w) == 0u);

  // Every third triangle gets normals (some unnormalised), every fifth UVs; values name the input.
  for (std::size_t i = 0; i < tris.size(); ++i) {
    SceneTriangle& t = tris[i];
    if (i % 3 == 0) {
      t.attributes |= kHasNormals;
      for (int k = 0; k < 3; ++k) t.n[k] = glm::vec3(0.0f, 0.0f, 2.0f + float(k));
      t.n[1] = glm::vec3(3.0f, 4.0f, 0.0f);
    }
    if (i % 5 == 0) {
      t.attributes |= kHasUv;
      for (int k = 0; k < 3; ++k) t.uv[k] = glm::vec2(float(i), float(k) + 0.25f);
    }
  }
  Bvh bvh = buildBvh(tris);
  std::vector<TriangleShading> s = buildTriangleShading(tris, bvh);
  REQUIRE(s.size() == bvh.triangles.size());
  for (std::size_t j = 0; j < s.size(); ++j) {
    const std::uint32_t i = bvh.order[j];
    CAPTURE(i);
    CHECK(bvh.order[as_uint(bvh.triangles[j].e1.w)] == i);  // e1.w: the canonical slot of input i
    CHECK(as_uint(bvh.triangles[j].e2.w) == tris[i].attributes);
    if (i % 3 == 0) {
      CHECK(glm::vec3(s[j].n0) == glm::vec3(0, 0, 1));
      CHECK(glm::vec3(s[j].n1) == glm::vec3(0.6f, 0.8f, 0.0f));
      CHECK(glm::vec3(s[j].n2) == glm::vec3(0, 0, 1));
    } else {
      CHECK(glm::vec3(s[j].n1) == glm::vec3(0.0f));
    }
    // surface_uv, as the stages read it (barycentrics u = 0.25, v = 0.5)
    const glm::vec2 uv = surface_uv(&bvh.triangles[j], &s[j], 0.25f, 0.5f);
    CHECK(uv == (i % 5 == 0 ? glm::vec2(float(i), 0.25f * 0.25f + 0.25f * 1.25f + 0.5f * 2.25f) : glm::vec2(0.0f)));
    if (i % 5 == 0) {
      CHECK(s[j].n0.w == float(i));
      CHECK(s[j].n2.w == float(i));
      CHECK(s[j].tv == glm::vec4(0.25f, 1.25f, 2.25f, 0.0f));
    } else {
      CHECK(s[j].tv == glm::vec4(0.0f));
    }
  }
}

// --- the pure rule (kernels/shared/shading.h) ----------------------------------------------------

namespace {

glm::vec3 tilted(float degrees) {  // the unit normal +y tilted toward +x
  const float a = glm::radians(degrees);
  return {std::sin(a), std::cos(a), 0.0f};
}

}  // namespace

TEST_CASE("shading normals: interpolation, orientation, the below-surface rule" * doctest::test_suite("cpu")) {
  const glm::vec3 n0(1, 0, 0), n1(0, 1, 0), n2(0, 0, 1);
  CHECK(interpolate_normal(n0, n1, n2, 0.0f, 0.0f) == n0);
  CHECK(interpolate_normal(n0, n1, n2, 1.0f, 0.0f) == n1);
  CHECK(interpolate_normal(n0, n1, n2, 0.0f, 1.0f) == n2);
  CHECK(glm::length(interpolate_normal(n0, n1, n2, 0.3f, 0.3f) - glm::normalize(glm::vec3(0.4f, 0.3f, 0.3f))) < 1e-6f);
  CHECK(interpolate_normal(n0, -n0, n2, 0.5f, 0.0f) == glm::vec3(0.0f));  // no direction: flat fallback
  CHECK(interpolate_normal(glm::vec3(NAN), n1, n2, 0.2f, 0.2f) == glm::vec3(0.0f));
  const glm::vec3 ng(0, 1, 0);
  CHECK(orient_to(-tilted(30), ng) == tilted(30));
  CHECK(orient_to(tilted(30), ng) == tilted(30));
  // A light direction below the geometric surface gives zero even where the shading normal says
  // it is lit (no leak); above it, the shading cosine.
  const glm::vec3 ns = tilted(50), below = glm::normalize(glm::vec3(1.0f, -0.2f, 0.0f));
  REQUIRE(glm::dot(ns, below) > 0.5f);
  CHECK(shading_cosine(ns, ng, below) == 0.0f);
  CHECK(pdf_cosine_folded(ns, ng, below) == 0.0f);
  const glm::vec3 above = glm::normalize(glm::vec3(0.3f, 0.5f, 0.2f));
  CHECK(shading_cosine(ns, ng, above) == glm::dot(ns, above));
  const glm::vec3 behindNs = glm::normalize(glm::vec3(-1.0f, 0.3f, 0.0f));  // above ng, below ns
  REQUIRE(glm::dot(behindNs, ns) < 0.0f);
  CHECK(shading_cosine(ns, ng, behindNs) == 0.0f);
  // Folding mirrors across the geometric plane and keeps directions above it as they are.
  CHECK(fold_above(above, ng) == above);
  CHECK(glm::length(fold_above(below, ng) - glm::vec3(below.x, -below.y, below.z)) < 1e-7f);
  // Flat frames are the flat formulas exactly.
  SurfaceFrame flat{glm::vec3(0), ng, ng, 0};
  CHECK(frame_cosine(flat, above) == glm::dot(ng, above));
  // The cosine lobe's pdf as the stages take it: the diffuse kind without a glossy lobe.
  const DiffuseBsdf lambert = diffuse_make(glm::vec3(0.5f), glm::vec3(0.0f), 1.0f);
  CHECK(diffuse_pdf(lambert, flat, above, above) == pdf_cosine_hemisphere(glm::dot(ng, above)));
  CHECK(cosine_weight(flat.ns, flat.ng, flat.smooth, above) == 1.0f);
  CHECK(frame_sample_direction(flat, glm::vec3(0.6f, 0.0f, 0.8f)) == to_world(glm::vec3(0.6f, 0.0f, 0.8f), ng));
}

TEST_CASE("folded cosine sampling: the pdf integrates to 1 and matches the sampler" * doctest::test_suite("cpu")) {
  const glm::vec3 ng(0, 1, 0);
  for (float degrees : {0.0f, 20.0f, 50.0f, 85.0f}) {
    CAPTURE(degrees);
    const glm::vec3 ns = tilted(degrees);
    // Midpoint quadrature over the sphere (y up): the pdf's integral, and that of the shading
    // cosine above the geometric surface (the direct-lighting integrand's angular part, / pi).
    const int nt = 1000, np = 2000;
    double total = 0.0, cosIntegral = 0.0;
    for (int i = 0; i < nt; ++i) {
      const double theta = M_PI * (i + 0.5) / nt, dA = std::sin(theta) * (M_PI / nt) * (2.0 * M_PI / np);
      for (int j = 0; j < np; ++j) {
        const double phi = 2.0 * M_PI * (j + 0.5) / np;
        const glm::vec3 w(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                          float(std::sin(theta) * std::sin(phi)));
        total += pdf_cosine_folded(ns, ng, w) * dA;
        cosIntegral += shading_cosine(ns, ng, w) * MCL_INV_PI * dA;
      }
    }
    CHECK(std::fabs(total - 1.0) < 2e-3);
    // E[cos / (pi p)] over folded samples is that integral; every sample lies above the surface.
    RunningStats est;
    SurfaceFrame s{glm::vec3(0), ng, ns, 1};
    const int n = 200000;
    for (int k = 0; k < n; ++k) {
      const glm::vec4 u = rng_uniform4(11, uint(k), 0, 0);
      const glm::vec3 w = frame_sample_direction(s, sample_cosine_hemisphere(u.x, u.y));
      REQUIRE(glm::dot(w, ng) >= 0.0f);
      est.add(cosine_weight(s.ns, s.ng, s.smooth, w));
    }
    INFO("integral " << cosIntegral << ", estimate " << est.mean << " +- " << est.standardError());
    CHECK(std::fabs(est.mean - cosIntegral) < 4.0 * est.standardError() + 2e-3);
    if (degrees == 0.0f) CHECK(est.variance() < 1e-12);  // no folding: f cos / p = 1 exactly
  }
}

// --- renders through the kernels ------------------------------------------------------------------

namespace {

Film renderWith(const Scene& s, const RenderOptions& o = {}, const DeviceInfo* device = nullptr) {
  static const DeviceInfo defaultDevice = selectDevice("");
  Bvh bvh = buildBvh(s.triangles);
  WavefrontRenderer r(device ? *device : defaultDevice, o);
  RenderStats stats;
  return r.render(s, bvh, stats);
}

// The unit sphere at the origin (rings x segments, with or without exact corner normals), seen
// from +z through a `size` x `size` camera that it nearly fills.
Scene sphereScene(bool withNormals, int size, int spp, int rings = 12, int segments = 24) {
  Scene s;
  s.path = "<sphere>";
  addUvSphere(s, glm::vec3(0.0f), 1.0f, rings, segments, withNormals);
  s.camera.position = {0.0f, 0.0f, 4.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.fovY = 32.0f;
  s.camera.width = s.camera.height = size;
  s.render.spp = spp;
  s.render.seed = 5;
  finishScene(s);
  return s;
}

// Mean angle (degrees) between the N AOV and the true unit-sphere normal where each pixel's centre
// ray meets the sphere, over the pixels whose centre ray passes within 0.9 of its centre.
double meanNormalErrorDegrees(const Scene& s, const std::function<glm::dvec3(std::size_t)>& normalOf, int* pixelsUsed) {
  const FrameParams fp = makeFrameParams(s.camera, s.render, 1);
  const glm::dvec3 o(s.camera.position);
  double sum = 0.0;
  int count = 0;
  for (int y = 0; y < s.camera.height; ++y)
    for (int x = 0; x < s.camera.width; ++x) {
      const glm::dvec3 d = glm::normalize(glm::dvec3(glm::vec3(fp.camTopLeft) + glm::vec3(fp.camDx) * (x + 0.5f) +
                                                     glm::vec3(fp.camDy) * (y + 0.5f)));
      const double b = glm::dot(o, d), c = glm::dot(o, o) - 1.0, disc = b * b - c;
      if (disc < 1.0 - 0.81) continue;  // impact parameter above 0.9 (or a miss)
      const glm::dvec3 truth = o + d * (-b - std::sqrt(disc));
      const std::size_t p = std::size_t(y) * s.camera.width + x;
      const glm::dvec3 n = glm::normalize(normalOf(p));
      sum += glm::degrees(std::acos(glm::clamp(glm::dot(n, glm::normalize(truth)), -1.0, 1.0)));
      ++count;
    }
  *pixelsUsed = count;
  return sum / count;
}
double meanNormalErrorDegrees(const Scene& s, const Film& f, int* pixelsUsed) {
  return meanNormalErrorDegrees(s, [&](std::size_t p) { return glm::dvec3(glm::vec3(f.aovSum[MCL_AOV_VECTORS * p + 1])); },
                                pixelsUsed);
}

}  // namespace

TEST_CASE("N AOV of a 12x24 sphere: with normals several times closer to the true normal than flat" * doctest::test_suite("opencl")) {
  RenderOptions o;
  o.aovs = true;
  int usedFlat = 0, usedSmooth = 0;
  const Scene flat = sphereScene(false, 48, 32), smooth = sphereScene(true, 48, 32);
  const double flatError = meanNormalErrorDegrees(flat, renderWith(flat, o), &usedFlat);
  const double smoothError = meanNormalErrorDegrees(smooth, renderWith(smooth, o), &usedSmooth);
  MESSAGE("mean angular error: flat " << flatError << " deg, smooth " << smoothError << " deg over " << usedFlat
                                   << " pixels");
  REQUIRE(usedFlat > 800);
  CHECK(usedSmooth == usedFlat);
  CHECK(flatError > 2.0);  // facets of 15 degrees
  CHECK(smoothError * 5.0 < flatError);
}

TEST_CASE("OBJ vn end to end: montecl render --aov normal of a 12x24 sphere is smooth with vn, faceted without" * doctest::test_suite("cli")) {
  // The same sphere as above, written as OBJ with and without `vn` and rendered by the real binary.
  TempDir dir;
  dir.write("probe.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n");
  std::vector<std::string> warnings;
  const Scene probe = loadScene(dir.file("probe.obj"), warnings);
  REQUIRE(!probe.triangles.empty());
  REQUIRE((probe.triangles[0].attributes & kHasNormals));  // the loader reads vn
  const Scene ref = sphereScene(true, 48, 16);
  double error[2];
  for (int withVn = 0; withVn < 2; ++withVn) {
    std::string obj;
    char line[160];
    int k = 0;
    for (const SceneTriangle& t : ref.triangles) {
      for (int c = 0; c < 3; ++c) {
        std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", t.v[c].x, t.v[c].y, t.v[c].z);
        obj += line;
        std::snprintf(line, sizeof line, "vn %.9g %.9g %.9g\n", t.n[c].x, t.n[c].y, t.n[c].z);
        if (withVn) obj += line;
      }
      if (withVn) std::snprintf(line, sizeof line, "f %d//%d %d//%d %d//%d\n", k + 1, k + 1, k + 2, k + 2, k + 3, k + 3);
      else std::snprintf(line, sizeof line, "f %d %d %d\n", k + 1, k + 2, k + 3);
      obj += line;
      k += 3;
    }
    const std::string name = withVn ? "smooth" : "flat";
    dir.write(name + ".obj", obj);
    dir.write(name + ".json", R"({"camera": {"position": [0, 0, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y": 32,
      "width": 48, "height": 48}, "meshes": [{"file": ")" + name + R"(.obj"}],
      "render": {"integrator": "ao", "spp": 16, "seed": 5}})");
    CliResult r = runMontecl({"render", dir.file(name + ".json"), "-o", dir.file(name + ".exr"), "--aov", "normal", "-q"});
    INFO(r.err);
    REQUIRE(r.exitCode == 0);
    LayeredImage img = readLayeredImage(dir.file(name + ".exr"));
    const std::vector<float>*nx = img.find("N.X"), *ny = img.find("N.Y"), *nz = img.find("N.Z");
    REQUIRE((nx && ny && nz));
    int used = 0;
    error[withVn] = meanNormalErrorDegrees(
        ref, [&](std::size_t p) { return glm::dvec3((*nx)[p], (*ny)[p], (*nz)[p]); }, &used);
    CHECK(used > 800);
  }
  MESSAGE("N AOV mean angular error through OBJ: without vn " << error[0] << " deg, with vn " << error[1] << " deg");
  CHECK(error[0] > 2.0);
  CHECK(error[1] * 5.0 < error[0]);
}

TEST_CASE("smooth sphere in open space: cosine AO exactly 1 everywhere, variance 0 (no dark rings)" * doctest::test_suite("opencl")) {
  Scene s = sphereScene(true, 24, 16, 6, 12);  // coarse: shading and geometric normals differ by up to 20 deg
  s.render.aoSampling = AoSampling::Cosine;
  s.render.background = glm::vec3(1.0f);  // misses count 1 too: every sample of every pixel is 1
  Film f = renderWith(s);
  for (std::size_t p = 0; p < f.mean.size(); ++p) {
    CAPTURE(p);
    REQUIRE(f.meanOf(p, 0) == 1.0);
    REQUIRE(f.m2Of(p, 0) == 0.0);
  }
  // Uniform hemisphere sampling estimates the same AO (1) with variance.
  s.render.aoSampling = AoSampling::Uniform;
  s.render.sampler = Sampler::Independent;  // z from var/n: i.i.d. samples
  s.render.background = glm::vec3(0.0f);
  s.camera.fovY = 6.0f;  // every pixel on the sphere
  ImageEstimate e = imageEstimate(renderWith(s));
  INFO("uniform AO " << e.mean << " +- " << e.standardError);
  CHECK(e.standardError > 0.0);
  CHECK(std::fabs(e.mean - 1.0) < 4.0 * e.standardError);
}

namespace {

// The floor y = 0 (albedo 0.5, 0.6, 0.7) whose every corner has the shading normal ns, and a square
// light (side `size`, centre c, front face toward the floor, Le = (2, 3, 4)), seen through a tiny
// field of view at the origin from the side.
Scene tiltedFloorUnderLight(glm::vec3 ns, glm::vec3 c, glm::vec3 lightNormal, float size, int spp) {
  Scene s;
  s.render.sampler = Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  s.path = "<tilted floor>";
  s.materials = {MaterialDesc{"floor", glm::vec3(0.5f, 0.6f, 0.7f)},
                 MaterialDesc{"light", glm::vec3(0.0f), glm::vec3(2.0f, 3.0f, 4.0f)}};
  addFloor(s, 0);
  for (SceneTriangle& t : s.triangles) {
    t.n[0] = t.n[1] = t.n[2] = ns;
    t.attributes = kHasNormals;
  }
  const glm::vec3 t = glm::normalize(glm::cross(lightNormal, glm::vec3(0, 0, 1))), b = glm::cross(lightNormal, t);
  const float h = size / 2;
  std::vector<glm::vec3> v = {c - t * h - b * h, c + t * h - b * h, c + t * h + b * h, c - t * h + b * h};
  if (glm::dot(glm::cross(v[1] - v[0], v[2] - v[0]), lightNormal) < 0) std::swap(v[1], v[3]);
  addQuad(s, v[0], v[1], v[2], v[3], 1);
  s.camera.position = {-2.0f, 0.3f, 0.1f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.fovY = 0.01f;
  s.camera.width = s.camera.height = 4;
  s.render.spp = spp;
  s.render.integrator = Integrator::Direct;
  finishScene(s);
  return s;
}

// Lambert's point-to-polygon form factor from the origin with normal n (polygon in n's hemisphere).
double formFactor(const std::vector<glm::vec3>& poly, glm::dvec3 n) {
  double sum = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const glm::dvec3 a = glm::normalize(glm::dvec3(poly[i])), b = glm::normalize(glm::dvec3(poly[(i + 1) % poly.size()]));
    sum += std::acos(glm::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, glm::normalize(glm::cross(a, b)));
  }
  return std::fabs(sum) / (2.0 * M_PI);
}

}  // namespace

TEST_CASE("direct light under a tilted shading normal: light, brdf and mis match the form factor about it" * doctest::test_suite("opencl")) {
  // Irradiance with a constant shading normal ns is Le F(ns) for a light above the geometric
  // surface and within ns's hemisphere; BRDF sampling folds the part of ns's lobe below the floor
  // (shared/shading.h), so its pdf is not the plain cosine one: a wrong pdf or weight shows here.
  struct Config {
    const char* name;
    float tilt;
    glm::vec3 c, normal;
    float size;
  };
  const std::vector<Config> configs = {
      {"overhead, tilt 50", 50.0f, {0, 1, 0}, {0, -1, 0}, 1.0f},
      {"overhead, tilt -30", -30.0f, {0.2f, 1, 0.1f}, {0, -1, 0}, 0.6f},
      {"low toward the tilt", 60.0f, {3, 0.6f, 0}, glm::normalize(glm::vec3(-1, -0.1f, 0)), 1.0f},
  };
  for (const Config& cfg : configs) {
    const glm::vec3 ns = tilted(cfg.tilt);
    Scene s = tiltedFloorUnderLight(ns, cfg.c, cfg.normal, cfg.size, 4096);
    std::vector<glm::vec3> poly = {s.triangles[2].v[0], s.triangles[2].v[1], s.triangles[2].v[2], s.triangles[3].v[2]};
    for (const glm::vec3& v : poly) REQUIRE(glm::dot(glm::normalize(v), ns) > 0.0f);  // the formula's premise
    const double F = formFactor(poly, glm::dvec3(ns));
    for (const char* strategy : {"light", "brdf", "mis"}) {
      s.render.directSampling = directSamplingNames().at(strategy);
      Film f = renderWith(s);
      for (int c = 0; c < 3; ++c) {
        const double expected = double(s.materials[0].albedo[c]) * s.materials[1].emission[c] * F;
        ImageEstimate e = imageEstimate(f, c);
        INFO(cfg.name << ", " << strategy << ": expected " << expected << " (F = " << F << "), got " << e.mean
                      << " +- " << e.standardError);
        CHECK(e.standardError > 0.0);
        CHECK(std::fabs(e.mean - expected) < 4.0 * e.standardError + 1e-4 * expected);
      }
    }
  }
}

TEST_CASE("no light through a surface: a two-sided emitter with tilted normals does not light itself" * doctest::test_suite("opencl")) {
  // A lone 2x2 plate emitting Le from both faces, shading normals tilted 60 degrees: half of the
  // cosine lobe around them lies below the plate. Without the rule, BRDF rays leaving below the
  // geometric surface would hit the plate's own back (an emitter) and add light through it.
  Scene s;
  s.path = "<plate>";
  s.materials = {MaterialDesc{"plate", glm::vec3(0.8f), glm::vec3(2.0f, 3.0f, 4.0f)}};
  s.materials[0].twoSidedEmission = true;
  addQuad(s, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0});
  const float a = glm::radians(60.0f);
  for (SceneTriangle& t : s.triangles) {
    t.n[0] = t.n[1] = t.n[2] = glm::vec3(std::sin(a), 0.0f, std::cos(a));
    t.attributes = kHasNormals;
  }
  s.camera.position = {0.1f, 0.2f, 3.0f};
  s.camera.target = {0.1f, 0.2f, 0.0f};
  s.camera.fovY = 10.0f;
  s.camera.width = s.camera.height = 8;
  s.render.spp = 16;
  s.render.integrator = Integrator::Direct;
  finishScene(s);
  for (float cameraZ : {3.0f, -3.0f}) {  // front and back
    s.camera.position.z = cameraZ;
    for (const char* strategy : {"brdf", "mis", "light"}) {
      s.render.directSampling = directSamplingNames().at(strategy);
      Film f = renderWith(s);
      CAPTURE(cameraZ);
      CAPTURE(strategy);
      for (std::size_t p = 0; p < f.mean.size(); ++p) {
        REQUIRE(f.meanOf(p, 0) == 2.0);
        REQUIRE(f.meanOf(p, 2) == 4.0);
      }
    }
  }
}

TEST_CASE("smooth shading: bit-identical across wave sizes and with the host backend" * doctest::test_suite("opencl")) {
  Scene s = sphereScene(true, 16, 4, 6, 12);
  addQuad(s, {-3, -1, -3}, {-3, -1, 3}, {3, -1, 3}, {3, -1, -3});  // a flat floor under it
  s.camera.fovY = 40.0f;
  finishScene(s);
  s.render.aoSampling = AoSampling::Uniform;
  RenderOptions o;
  o.aovs = true;
  const Film reference = renderWith(s, o);
  for (std::uint64_t wave : {1ull, 97ull, 16ull * 16 * 4}) {
    o.waveSize = wave;
    CAPTURE(wave);
    Film f = renderWith(s, o);
    CHECK(f.mean == reference.mean);
    CHECK(f.m2 == reference.m2);
    CHECK(f.aovSum == reference.aovSum);
  }
  const DeviceInfo host = selectDevice("host");
  Film h = renderWith(s, o, &host);
  for (std::size_t p = 0; p < h.mean.size(); ++p) {
    CAPTURE(p);
    CHECK(std::fabs(h.meanOf(p, 0) - reference.meanOf(p, 0)) <= 1e-5 * std::fabs(reference.meanOf(p, 0)) + 1e-7);
  }
}

}  // namespace test_file_shading
