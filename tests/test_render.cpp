// test_render.cpp: the AO estimator through the real wavefront kernels on the default OpenCL
// device: exact values where the variance is zero, z-scores against the estimator's own standard
// error elsewhere, against analytic answers, and bit-identical results across seeds, wave sizes
// and work-group sizes.
#include <doctest/doctest.h>

#include <cmath>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "render/frame_params.h"
#include "render/stage_runner.h"
#include "render/wavefront.h"
#include "film_stats.h"
#include "stats.h"
#include "nan_wave.h"
#include "test_scenes.h"

namespace test_file_render {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

Film renderScene(const Scene& scene, RenderOptions options = {}) {
  static const DeviceInfo device = selectDevice("");
  Bvh bvh = buildBvh(scene.triangles);
  WavefrontRenderer renderer(device, options);
  RenderStats stats;
  return renderer.render(scene, bvh, stats);
}

// Per-pixel mean and variance of the mean of the red channel.
void pixelMeanVar(const Film& f, std::size_t p, double& mean, double& varOfMean) {
  double var;
  montecl_test::pixelMeanVar(f, p, 0, mean, varOfMean, var);
}


bool sameFilm(const Film& a, const Film& b) {
  return a.mean == b.mean && a.m2 == b.m2;
}

}  // namespace

TEST_CASE("AO of an open plane is exactly 1 with cosine sampling" * doctest::test_suite("opencl")) {
  Scene s = floorScene({0, 0, 0}, 1.0f, 60.0f, 32, 16);
  s.render.aoSampling = montecl::AoSampling::Cosine;
  Film f = renderScene(s);
  for (std::size_t p = 0; p < f.mean.size(); ++p) {
    REQUIRE(double(f.count[p]) == 16.0f);
    REQUIRE(f.mean[p].x == 1.0f);
    REQUIRE(f.mean[p].y == 1.0f);
    REQUIRE(f.mean[p].z == 1.0f);
  }
}

TEST_CASE("AO of an open plane is 1 within 4 standard errors with uniform sampling" * doctest::test_suite("opencl")) {
  Scene s = floorScene({0, 0, 0}, 1.0f, 60.0f, 32, 64);
  s.render.aoSampling = montecl::AoSampling::Uniform;
  s.render.sampler = montecl::Sampler::Independent;  // per-pixel z from var/n: i.i.d. samples
  Film f = renderScene(s);
  ImageEstimate e = imageEstimate(f);
  INFO("mean " << e.mean << " +- " << e.standardError);
  CHECK(e.standardError > 0.0);
  CHECK(std::fabs(e.mean - 1.0) < 4.0 * e.standardError);
  // Per pixel: the z-scores against each pixel's own standard error look standard normal.
  int outliers = 0;
  double zSum = 0;
  for (std::size_t p = 0; p < f.mean.size(); ++p) {
    double m, v;
    pixelMeanVar(f, p, m, v);
    double z = (m - 1.0) / std::sqrt(v);
    zSum += z;
    if (std::fabs(z) > 4.0) ++outliers;
  }
  CHECK(outliers <= 1);
  CHECK(std::fabs(zSum / f.mean.size()) < 0.2);
}

TEST_CASE("sobol: AO of an open plane with uniform sampling is 1 within 4 SE over 16 seeds" * doctest::test_suite("opencl")) {
  // Within one render the Sobol samples are correlated; the seeds' image means are independent.
  Scene s = floorScene({0, 0, 0}, 1.0f, 60.0f, 8, 16);
  s.render.aoSampling = montecl::AoSampling::Uniform;
  s.render.sampler = montecl::Sampler::Sobol;
  std::vector<double> means;
  for (std::uint32_t seed = 0; seed < 16; ++seed) {
    s.render.seed = seed;
    means.push_back(imageMean(renderScene(s)));
  }
  ImageEstimate e = acrossRenders(means);
  INFO("mean " << e.mean << " +- " << e.standardError);
  CHECK(e.standardError > 0.0);
  CHECK(e.standardError < 0.01);  // the test can see a 4% bias
  CHECK(std::fabs(e.mean - 1.0) < 4.0 * e.standardError);
}

TEST_CASE("AO beside an infinite wall is 1/2 for both samplings, and they agree per pixel" * doctest::test_suite("opencl")) {
  Scene s = wallScene(24, 256);
  s.render.aoSampling = montecl::AoSampling::Uniform;
  s.render.sampler = montecl::Sampler::Independent;  // z from var/n: i.i.d. samples
  Film uni = renderScene(s);
  s.render.aoSampling = montecl::AoSampling::Cosine;
  Film cos = renderScene(s);
  for (const Film* f : {&uni, &cos}) {
    ImageEstimate e = imageEstimate(*f);
    INFO("mean " << e.mean << " +- " << e.standardError);
    CHECK(std::fabs(e.mean - 0.5) < 4.0 * e.standardError + 2e-3);  // 2e-3: the wall is finite
  }
  int outliers = 0;
  double zSum = 0;
  for (std::size_t p = 0; p < uni.mean.size(); ++p) {
    double mu, vu, mc, vc;
    pixelMeanVar(uni, p, mu, vu);
    pixelMeanVar(cos, p, mc, vc);
    REQUIRE(vu + vc > 0.0);
    double z = (mu - mc) / std::sqrt(vu + vc);
    zSum += z;
    if (std::fabs(z) > 4.0) ++outliers;
  }
  CHECK(outliers <= 1);
  CHECK(std::fabs(zSum / uni.mean.size()) < 0.25);
}

TEST_CASE("ao_distance shorter than the wall's distance gives exactly 1 with cosine sampling" * doctest::test_suite("opencl")) {
  Scene s = wallScene(16, 8);
  s.render.aoSampling = montecl::AoSampling::Cosine;
  s.render.aoDistance = 0.2f;  // the floor seen lies 0.3 .. 0.7 from the wall
  s.camera.fovY = 20.0f;
  Film f = renderScene(s);
  for (std::size_t p = 0; p < f.mean.size(); ++p) REQUIRE(f.mean[p].x == 1.0f);
}

TEST_CASE("a camera ray that hits nothing gives the background" * doctest::test_suite("opencl")) {
  Scene s = floorScene({0, 0, 0}, 1.0f, 60.0f, 8, 4);
  s.camera.target = s.camera.position + glm::vec3(0, 1, 0);  // look up, away from the floor
  s.camera.up = {0, 0, 1};
  s.render.background = {0.25f, 0.5f, 2.0f};
  Film f = renderScene(s);
  std::vector<float> rgb = f.meanRgb();
  for (std::size_t p = 0; p < f.mean.size(); ++p) {
    REQUIRE(rgb[3 * p + 0] == 0.25f);
    REQUIRE(rgb[3 * p + 1] == 0.5f);
    REQUIRE(rgb[3 * p + 2] == 2.0f);
  }
}

TEST_CASE("images are bit-identical for the same seed, whatever the wave or work-group size" * doctest::test_suite("opencl")) {
  Scene s = wallScene(20, 6);
  s.render.aoSampling = montecl::AoSampling::Uniform;
  s.render.seed = 3;
  Film reference = renderScene(s);
  for (std::uint64_t wave : {1ull, 97ull, 400ull, 1000ull, 20ull * 20 * 6}) {
    RenderOptions o;
    o.waveSize = wave;
    CAPTURE(wave);
    CHECK(sameFilm(renderScene(s, o), reference));
  }
  for (std::size_t wg : {1u, 7u, 32u}) {
    RenderOptions o;
    o.workGroupSize = wg;
    CAPTURE(wg);
    CHECK(sameFilm(renderScene(s, o), reference));
  }
  CHECK(sameFilm(renderScene(s), reference));
  s.render.seed = 4;
  CHECK_FALSE(sameFilm(renderScene(s), reference));
}

TEST_CASE("images are bit-identical with the wide and the binary BVH layout" * doctest::test_suite("opencl")) {
  Scene wall = wallScene(20, 6);
  wall.render.aoSampling = montecl::AoSampling::Uniform;
  Scene demo = montecl_test::smallDemoScene(32, 24, 4);
  for (Scene* s : {&wall, &demo}) {
    RenderOptions wide, binary;
    wide.bvhLayout = BvhLayout::Wide;
    binary.bvhLayout = BvhLayout::Binary;
    CHECK(sameFilm(renderScene(*s, wide), renderScene(*s, binary)));
  }
}

TEST_CASE("NaN camera rays are misses and every one is counted, in both BVH layouts" * doctest::test_suite("opencl")) {
  // Without the fix there is no count, and the wide kernel read an empty slot (SIGSEGV in PoCL).
  for (BvhLayout layout : {BvhLayout::Wide, BvhLayout::Binary}) {
    CAPTURE(int(layout));
    std::unique_ptr<StageRunner> run = makeClStageRunner(selectDevice(""), 0, layout);
    checkNanCameraWave(*run, floorScene({0, 0, 0}, 1.0f, 60.0f, 16, 1));
  }
}

}  // namespace test_file_render
