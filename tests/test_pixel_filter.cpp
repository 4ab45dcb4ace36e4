// test_pixel_filter.cpp: the pixel filters (render.filter, --filter): a sharp edge rendered with each
// filter against the edge convolved with the filter, computed here from the filters' formulas
// (z-scores against the estimator's binomial standard error, floored at half a sample); the text and scene-file forms; bad filters as
// one error line, exit 2.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <string>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "render/wavefront.h"
#include "scene/pixel_filter.h"
#include "test_scenes.h"

namespace test_file_pixel_filter {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

// The filters written again from their definitions (pbrt-v4's), not from pixel_filter.cpp.
double sincOf(double x) { return x == 0.0 ? 1.0 : std::sin(M_PI * x) / (M_PI * x); }
double mitchellOf(double x, double b, double c) {
  x = std::fabs(x);
  if (x >= 2.0) return 0.0;
  if (x < 1.0) return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) / 6;
  return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x + (8 * b + 24 * c)) / 6;
}

struct FilterCase {
  std::string text;
  double radius;
  std::function<double(double)> weight;  // the 1D filter, negative lobes clamped to 0
};

std::vector<FilterCase> filterCases() {
  return {
      {"box", 0.5, [](double) { return 1.0; }},
      {"box,radius=1.5", 1.5, [](double) { return 1.0; }},
      {"triangle", 2.0, [](double x) { return 2.0 - std::fabs(x); }},
      {"triangle,radius=0.75", 0.75, [](double x) { return 0.75 - std::fabs(x); }},
      {"gaussian,radius=1.5,sigma=0.5", 1.5,
       [](double x) { return std::exp(-x * x / 0.5) - std::exp(-1.5 * 1.5 / 0.5); }},
      {"mitchell", 2.0, [](double x) { return std::max(0.0, mitchellOf(x, 1.0 / 3, 1.0 / 3)); }},
      {"lanczos,radius=3,tau=3", 3.0, [](double x) { return std::max(0.0, sincOf(x) * sincOf(x / 3)); }},
  };
}

// The probability that an offset drawn from the filter lies below t (Simpson's rule, 20000 steps).
double filterCdfAt(const FilterCase& fc, double t) {
  auto integral = [&](double a, double b) {
    if (!(b > a)) return 0.0;
    const int n = 20000;
    const double h = (b - a) / n;
    double s = fc.weight(a) + fc.weight(b);
    for (int i = 1; i < n; ++i) s += fc.weight(a + i * h) * (i % 2 ? 4.0 : 2.0);
    return s * h / 3.0;
  };
  const double r = fc.radius;
  return integral(-r, std::min(std::max(t, -r), r)) / integral(-r, r);
}

}  // namespace

TEST_CASE("filter: a sharp edge rendered with each filter is the edge convolved with the filter, within 4.5 SE" *
          doctest::test_suite("opencl")) {
  // An emitter (Le 1) fills the image left of x = xEdge in the plane z = 0, seen straight on from
  // z = 1: its edge is a vertical line at pixel coordinate e (pixel c spans [c, c + 1)). With
  // emitters only (max depth 1) a sample is 1 or 0, so pixel c's expected value is the chance that
  // its sample's offset from the pixel centre is below e - c - 0.5: the filter's CDF there.
  const int width = 24, height = 6, spp = 512;
  const float fovY = 30.0f;
  const double pixel = 2.0 * std::tan(double(fovY) * M_PI / 360.0) / height;  // world units at z = 0
  const double e = width / 2.0 + 0.37;
  const float xEdge = float((e - width / 2.0) * pixel);
  Scene s;
  s.camera.position = {0.0f, 0.0f, 1.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.fovY = fovY;
  s.camera.width = width;
  s.camera.height = height;
  MaterialDesc light("light", glm::vec3(0.0f), glm::vec3(1.0f));
  s.materials.push_back(light);
  addQuad(s, {-100.0f, -100.0f, 0.0f}, {xEdge, -100.0f, 0.0f}, {xEdge, 100.0f, 0.0f}, {-100.0f, 100.0f, 0.0f}, 0);
  finishScene(s);
  s.render.integrator = Integrator::Path;
  s.render.maxDepth = 1;
  s.render.sampler = Sampler::Independent;  // i.i.d. samples: the binomial standard error holds
  s.render.spp = spp;
  const Bvh bvh = buildBvh(s.triangles);
  const DeviceInfo device = selectDevice("");
  for (const FilterCase& fc : filterCases()) {
    CAPTURE(fc.text);
    std::string problem;
    REQUIRE(parseFilterText(fc.text, s.render.filter, &problem));
    WavefrontRenderer renderer(device, RenderOptions{});
    RenderStats stats;
    const Film f = renderer.render(s, bvh, stats);
    double worst = 0.0, spread = 0.0;
    for (int c = 0; c < width; ++c) {
      double sum = 0.0;
      for (int row = 0; row < height; ++row) sum += f.mean[std::size_t(row * width + c)].x;
      const double mean = sum / height, expected = filterCdfAt(fc, e - c - 0.5);
      // The binomial standard error, floored at half of one sample's share (0.5 / n): where the
      // expectation is 0 or 1 (outside the filter's reach) two stray samples still fail the test.
      const double n = double(height) * spp, se = std::max(std::sqrt(expected * (1 - expected) / n), 0.5 / n);
      const double z = (mean - expected) / se;
      CAPTURE(c);
      CAPTURE(mean);
      CAPTURE(expected);
      CHECK(std::fabs(z) < 4.5);
      worst = std::max(worst, std::fabs(z));
      if (expected > 0.01 && expected < 0.99) spread += 1.0;
    }
    CHECK(spread >= 1.0);  // the edge is blurred over at least one pixel: the case tests something
    MESSAGE(fc.text << ": largest |z| " << worst);
  }
}

TEST_CASE("filter: text and scene-file forms; the default box is the pixel itself" * doctest::test_suite("cpu")) {
  PixelFilter f;
  std::string problem;
  CHECK(filterText(PixelFilter{}) == "box");
  REQUIRE(parseFilterText("gaussian,radius=2,sigma=0.25", f, &problem));
  CHECK(f.type == FilterType::Gaussian);
  CHECK(f.radius == 2.0f);
  CHECK(f.sigma == 0.25f);
  CHECK(filterText(f) == "gaussian,radius=2,sigma=0.25");
  REQUIRE(parseFilterText("mitchell", f, &problem));
  CHECK(f.radius == 2.0f);
  CHECK(filterHasNegativeLobes(f));
  CHECK(filterKernelKind(f) == MCL_FILTER_TABLE);
  const std::array<float, MCL_FILTER_BINS> cdf = filterCdf(f);
  for (int i = 1; i < MCL_FILTER_BINS; ++i) CHECK(cdf[std::size_t(i)] >= cdf[std::size_t(i - 1)]);
  CHECK(cdf[MCL_FILTER_BINS - 1] == 1.0f);
  CHECK(cdf[MCL_FILTER_BINS / 2 - 1] == doctest::Approx(0.5).epsilon(1e-5));  // symmetric
  CHECK(!parseFilterText("blackman", f, &problem));
  CHECK(problem.find("unknown filter 'blackman'") != std::string::npos);
  CHECK(!parseFilterText("gaussian,radius=-1", f, &problem));
  CHECK(problem.find("radius") != std::string::npos);
  CHECK(!parseFilterText("gaussian,tau=2", f, &problem));
  CHECK(problem.find("no parameter 'tau'") != std::string::npos);
  CHECK(!parseFilterText("box,radius", f, &problem));
  // Scene file: a name or an object.
  std::vector<std::string> warnings;
  const JsonCtx ctx{"s.json", warnings};
  CHECK(filterFromJson(ctx, nlohmann::json("triangle"), "render.filter").type == FilterType::Triangle);
  const PixelFilter g = filterFromJson(ctx, nlohmann::json::parse(R"({"type": "gaussian", "radius": 1.5, "sigma": 0.4})"),
                                       "render.filter");
  CHECK(g.sigma == 0.4f);
  CHECK_THROWS_WITH_AS(filterFromJson(ctx, nlohmann::json::parse(R"({"type": "gaussian", "sigma": -1})"), "render.filter"),
                       doctest::Contains("render.filter.sigma"), std::exception);
}

TEST_CASE("filter: bad --filter and render.filter are one error line, exit 2; mitchell warns of its clamped lobes" *
          doctest::test_suite("cli")) {
  TempDir dir;
  const std::string out = dir.path + "/o.pfm";
  CliResult r = renderOnHost(demoScene(), out, {"--filter", "gaussian,radius=0"});
  CHECK(r.exitCode == 2);
  CHECK(oneLine(r.err));
  CHECK(r.err.find("radius") != std::string::npos);
  r = renderOnHost(demoScene(), out, {"--filter", "sinc"});
  CHECK(r.exitCode == 2);
  CHECK(oneLine(r.err));
  const std::string scene = dir.path + "/s.json";
  {
    std::ofstream(scene) << R"({"camera": {"position": [0, 1.6, 5.0], "target": [0, 0.55, -0.6]},
      "meshes": [{"file": ")" << MONTECL_SOURCE_DIR << R"(/scenes/demo/demo.obj"}],
      "render": {"filter": {"type": "lanczos", "radius": 99}}})";
  }
  r = renderOnHost(scene, out);
  CHECK(r.exitCode == 2);
  CHECK(oneLine(r.err));
  CHECK(r.err.find("render.filter.radius") != std::string::npos);
  r = renderOnHost(demoScene(), out, {"--filter", "mitchell"});
  CHECK(r.exitCode == 0);
  CHECK(r.err.find("negative lobes are clamped") != std::string::npos);
}

}  // namespace test_file_pixel_filter
