// test_path.cpp: the path tracer (--integrator path) and the thin lens through the real kernels:
// the furnace (a closed box of albedo a emitting Le everywhere: L = Le / (1 - a), and
// Le (1 - a^D) / (1 - a) at --max-depth D) within 4 standard errors, Russian roulette unbiased;
// depth 1 shows emitters only (every sample exactly 0 or Le); depth 2 equals the direct
// integrator with MIS per pixel (z-scores) on a Cornell-like box; path images bit-identical across
// wave sizes and work-group sizes; the thin lens: aperture 0 is the pinhole bit for bit, a plane
// in focus stays sharp and defocus blur grows with the aperture; bad --max-depth / --rr-depth /
// aperture / focus input.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "cli_runner.h"
#include "film_stats.h"
#include "render/wavefront.h"
#include "test_scenes.h"

namespace test_file_path {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;
namespace fs = std::filesystem;

namespace {

Film render(const Scene& scene, RenderOptions options = {}, const std::string& device = "") {
  const DeviceInfo info = selectDevice(device);
  Bvh bvh = buildBvh(scene.triangles);
  WavefrontRenderer renderer(info, options);
  RenderStats stats;
  return renderer.render(scene, bvh, stats);
}

Scene withPath(Scene s, int maxDepth, int rrDepth = 5) {
  s.render.integrator = Integrator::Path;
  s.render.maxDepth = maxDepth;
  s.render.rrDepth = rrDepth;
  s.render.sampler = Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  return s;
}

// The rectangle corner, corner + u, corner + u + v, corner + v with its front face toward `front`.
void addRect(Scene& s, glm::vec3 corner, glm::vec3 u, glm::vec3 v, glm::vec3 front, std::uint32_t material) {
  if (glm::dot(glm::cross(u, v), front) >= 0.0f)
    addQuad(s, corner, corner + u, corner + u + v, corner + v, material);
  else
    addQuad(s, corner, corner + v, corner + u + v, corner + u, material);
}

// Axis-aligned box [lo, hi], faces in front of `inward` (true: toward the inside).
void addBox(Scene& s, glm::vec3 lo, glm::vec3 hi, bool inward, std::uint32_t material, bool bottom = true) {
  const glm::vec3 d = hi - lo, c = (lo + hi) * 0.5f;
  const glm::vec3 ex(d.x, 0, 0), ey(0, d.y, 0), ez(0, 0, d.z);
  const float sign = inward ? 1.0f : -1.0f;
  auto face = [&](glm::vec3 corner, glm::vec3 u, glm::vec3 v) {
    glm::vec3 mid = corner + (u + v) * 0.5f;
    addRect(s, corner, u, v, (c - mid) * sign, material);
  };
  if (bottom) face(lo, ex, ez);
  face(lo + ey, ex, ez);
  face(lo, ey, ez);
  face(lo + ex, ey, ez);
  face(lo, ex, ey);
  face(lo + ez, ex, ey);
}

const glm::vec3 kFurnaceAlbedo(0.3f, 0.5f, 0.7f);
const glm::vec3 kFurnaceLe(1.0f, 2.0f, 0.5f);

// A closed box, every face albedo kFurnaceAlbedo emitting kFurnaceLe from both sides, seen from
// inside by a size x size camera.
Scene furnaceScene(int size, int spp) {
  Scene s;
  s.path = "<furnace>";
  MaterialDesc m{"wall", kFurnaceAlbedo, kFurnaceLe};
  m.twoSidedEmission = true;
  s.materials = {m};
  addBox(s, glm::vec3(-1.0f), glm::vec3(1.0f), true, 0);
  s.camera.position = {0.1f, -0.2f, 0.05f};
  s.camera.target = {0.3f, 0.1f, 1.0f};
  s.camera.fovY = 60.0f;
  s.camera.width = s.camera.height = size;
  s.render.spp = spp;
  s.render.seed = 3;
  finishScene(s);
  return s;
}

// A Cornell-like box [0, 1]^3 open toward the camera (+z): white floor, ceiling and back, red left,
// green right wall, a white block, and a one-sided square light under the ceiling facing down.
const glm::vec3 kLightLe(8.0f, 7.0f, 5.0f);
Scene cornellLike(int size, int spp) {
  Scene s;
  s.render.sampler = Sampler::Independent;  // its z-tests take the error from var/n: i.i.d. samples
  s.path = "<cornell-like>";
  s.materials = {MaterialDesc{"white", glm::vec3(0.7f), glm::vec3(0.0f)},
                 MaterialDesc{"red", glm::vec3(0.6f, 0.1f, 0.1f), glm::vec3(0.0f)},
                 MaterialDesc{"green", glm::vec3(0.1f, 0.6f, 0.1f), glm::vec3(0.0f)},
                 MaterialDesc{"light", glm::vec3(0.0f), kLightLe}};
  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  addRect(s, glm::vec3(0), x, z, y, 0);          // floor
  addRect(s, y, x, z, -y, 0);                    // ceiling
  addRect(s, glm::vec3(0), x, y, z, 0);          // back
  addRect(s, glm::vec3(0), y, z, x, 1);          // left (red)
  addRect(s, x, y, z, -x, 2);                    // right (green)
  addRect(s, glm::vec3(0.37f, 0.98f, 0.38f), x * 0.26f, z * 0.24f, -y, 3);  // light, facing down
  addBox(s, {0.55f, 0.0f, 0.25f}, {0.8f, 0.45f, 0.5f}, false, 0, false);     // block
  s.camera.position = {0.5f, 0.5f, 2.3f};
  s.camera.target = {0.5f, 0.5f, 0.5f};
  s.camera.fovY = 38.0f;
  s.camera.width = s.camera.height = size;
  s.render.spp = spp;
  finishScene(s);
  return s;
}

bool sameFilm(const Film& a, const Film& b) {
  const auto same = [](const std::vector<glm::vec4>& x, const std::vector<glm::vec4>& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(glm::vec4)) == 0;
  };
  return same(a.mean, b.mean) && same(a.meanLo, b.meanLo) && same(a.m2, b.m2) && same(a.m2Lo, b.m2Lo) &&
         a.count == b.count;
}

}  // namespace

TEST_CASE("path: furnace, unlimited depth: L = Le / (1 - a) within 4 SE, Russian roulette unbiased" * doctest::test_suite("opencl")) {
  for (int rrDepth : {1, 5}) {
    Film f = render(withPath(furnaceScene(8, 256), -1, rrDepth));
    for (int c = 0; c < 3; ++c) {
      const double expected = kFurnaceLe[c] / (1.0 - kFurnaceAlbedo[c]);
      ImageEstimate e = imageEstimate(f, c);
      INFO("rr depth " << rrDepth << ", channel " << c << ": " << e.mean << " +- " << e.standardError << ", expected "
                       << expected);
      CHECK(std::fabs(e.mean - expected) <= 4.0 * e.standardError);
      CHECK(e.standardError < 0.01 * expected);  // the test can see a 4% bias
      CHECK(e.standardError > 0.0);
    }
  }
}

TEST_CASE("sobol: path furnace, unlimited depth: L = Le / (1 - a) within 4 SE over 16 seeds" * doctest::test_suite("opencl")) {
  // The standard error from the spread of independently seeded renders (Sobol samples within one
  // render are correlated).
  std::vector<std::vector<double>> means(3);
  for (std::uint32_t seed = 0; seed < 16; ++seed) {
    Scene s = withPath(furnaceScene(8, 32), -1, 1);
    s.render.sampler = Sampler::Sobol;
    s.render.seed = seed;
    Film f = render(s);
    for (int c = 0; c < 3; ++c) means[size_t(c)].push_back(imageMean(f, c));
  }
  for (int c = 0; c < 3; ++c) {
    const double expected = kFurnaceLe[c] / (1.0 - kFurnaceAlbedo[c]);
    ImageEstimate e = acrossRenders(means[size_t(c)]);
    INFO("channel " << c << ": " << e.mean << " +- " << e.standardError << ", expected " << expected);
    CHECK(e.standardError > 0.0);
    CHECK(e.standardError < 0.01 * expected);
    CHECK(std::fabs(e.mean - expected) <= 4.0 * e.standardError);
  }
}

TEST_CASE("path: furnace at --max-depth D: L = Le (1 - a^D) / (1 - a); D = 1 is exactly Le" * doctest::test_suite("opencl")) {
  for (int depth : {1, 2, 3, 6}) {
    Film f = render(withPath(furnaceScene(8, 128), depth, 3));
    for (int c = 0; c < 3; ++c) {
      const double a = kFurnaceAlbedo[c];
      const double expected = kFurnaceLe[c] * (1.0 - std::pow(a, depth)) / (1.0 - a);
      ImageEstimate e = imageEstimate(f, c);
      INFO("depth " << depth << ", channel " << c << ": " << e.mean << " +- " << e.standardError << ", expected "
                    << expected);
      if (depth == 1) {
        CHECK(e.mean == doctest::Approx(expected).epsilon(1e-7));
        CHECK(e.standardError == 0.0);
      } else {
        CHECK(std::fabs(e.mean - expected) <= 4.0 * e.standardError);
        CHECK(e.standardError < 0.01 * expected);
      }
    }
  }
}

TEST_CASE("path: --max-depth 1 shows emitters only: every sample is exactly 0 or Le" * doctest::test_suite("opencl")) {
  Film f = render(withPath(cornellLike(24, 64), 1));
  int lit = 0, dark = 0;
  for (std::size_t p = 0; p < f.mean.size(); ++p) {
    const double n = double(f.count[p]);
    for (int c = 0; c < 3; ++c) {
      // Samples in {0, Le}: mean m = k Le / n and M2 = n m (Le - m) exactly (up to float rounding).
      const double m = f.meanOf(p, c), le = kLightLe[c];
      CAPTURE(p);
      CHECK(m >= 0.0);
      CHECK(m <= le * (1.0 + 1e-6));
      CHECK(f.m2Of(p, c) == doctest::Approx(n * m * (le - m)).epsilon(1e-4).scale(le * le));
    }
    if (f.meanOf(p, 0) == 0.0) ++dark;
    else ++lit;
  }
  CHECK(lit > 0);
  CHECK(dark > int(f.mean.size()) / 2);
}

TEST_CASE("path: --max-depth 2 equals --integrator direct --direct-sampling mis per pixel (z-scores)" * doctest::test_suite("opencl")) {
  Scene s = cornellLike(16, 512);
  s.render.seed = 21;
  Film path = render(withPath(s, 2));
  s.render.integrator = Integrator::Direct;
  s.render.directSampling = DirectSampling::Mis;
  s.render.seed = 22;
  Film direct = render(s);
  for (int c = 0; c < 3; ++c) {
    int outliers = 0, compared = 0, exact = 0;
    double zSum = 0.0, totalDiff = 0.0, totalVar = 0.0;
    for (std::size_t p = 0; p < path.mean.size(); ++p) {
      double mp, vp, sp, md, vd, sd;
      pixelMeanVar(path, p, c, mp, vp, sp);
      pixelMeanVar(direct, p, c, md, vd, sd);
      totalDiff += mp - md;
      totalVar += vp + vd;
      if (vp + vd == 0.0) {
        CHECK(mp == md);  // background, or only the light seen directly
        ++exact;
        continue;
      }
      const double z = (mp - md) / std::sqrt(vp + vd);
      zSum += z;
      ++compared;
      if (std::fabs(z) > 4.0) ++outliers;
    }
    INFO("channel " << c << ": outliers " << outliers << " of " << compared << " (" << exact << " exact), mean z "
                    << zSum / compared << ", image difference " << totalDiff << " +- " << std::sqrt(totalVar));
    CHECK(compared > int(path.mean.size()) / 2);
    CHECK(outliers <= 1);
    CHECK(std::fabs(zSum / compared) < 4.0 / std::sqrt(double(compared)));
    CHECK(std::fabs(totalDiff) <= 4.0 * std::sqrt(totalVar));
  }
  // And the bounces matter: at unlimited depth the image is brighter than direct lighting alone.
  Film full = render(withPath(cornellLike(16, 64), -1));
  CHECK(imageMean(full, 1) > 1.2 * imageMean(direct, 1));
}

TEST_CASE("path: images are bit-identical for any wave size and work-group size, and on the host backend" * doctest::test_suite("opencl")) {
  Scene s = withPath(cornellLike(12, 6), -1, 2);
  s.render.lightSamples = 2;
  RenderOptions o;
  Film reference = render(s, o);
  for (std::uint64_t wave : {7ull, 37ull, 500ull}) {
    o.waveSize = wave;
    CHECK_MESSAGE(sameFilm(reference, render(s, o)), "wave size " << wave);
  }
  o = RenderOptions{};
  o.workGroupSize = 1;
  CHECK_MESSAGE(sameFilm(reference, render(s, o)), "work-group size 1");
  o.workGroupSize = 0;
  for (std::uint64_t wave : {0ull, 53ull}) {
    o.waveSize = wave;
    Film host = render(s, o, "host");
    // Across devices too: the path's directions use no built-in sin/cos (sampling.h, portable).
    CHECK_MESSAGE(sameFilm(reference, host), "host backend vs OpenCL, wave size " << wave);
  }
}

namespace {

// An emitting plane (z = -planeZ) covering the image's left half (its edge x = 0.01 runs through a
// pixel column), seen at --max-depth 1 through a lens focused at focusDistance: the edge's width in
// columns whose value lies strictly between 0 and Le.
Scene edgeScene(float apertureRadius, float focusDistance) {
  Scene s;
  s.path = "<edge>";
  s.materials = {MaterialDesc{"light", glm::vec3(0.0f), glm::vec3(1.0f)}};
  addRect(s, {-50.0f, -50.0f, -2.0f}, {50.01f, 0.0f, 0.0f}, {0.0f, 100.0f, 0.0f}, {0, 0, 1}, 0);
  s.camera.position = {0.0f, 0.0f, 0.0f};
  s.camera.target = {0.0f, 0.0f, -1.0f};
  s.camera.fovY = 10.0f;
  s.camera.width = 41;
  s.camera.height = 3;
  s.camera.apertureRadius = apertureRadius;
  s.camera.focusDistance = focusDistance;
  s.render.spp = 256;
  finishScene(s);
  return withPath(s, 1);
}

int blurredColumns(const Film& f, int width) {
  int columns = 0;
  for (int x = 0; x < width; ++x) {
    const double v = f.meanOf(std::size_t(width + x), 0);  // middle row
    columns += v > 0.01 && v < 0.99;
  }
  return columns;
}

}  // namespace

TEST_CASE("thin lens: aperture 0 is the pinhole bit for bit; in focus stays sharp; blur grows with aperture" * doctest::test_suite("opencl")) {
  const Film pinhole = render(edgeScene(0.0f, 0.0f));
  CHECK(sameFilm(pinhole, render(edgeScene(0.0f, 0.7f))));
  const int sharp = blurredColumns(pinhole, 41);
  CHECK(sharp <= 1);
  // Focused on the plane: every lens ray of a pixel sample meets the plane at the pinhole ray's point.
  const Film focused = render(edgeScene(0.05f, 2.0f));
  CHECK(blurredColumns(focused, 41) == sharp);
  double worst = 0.0;
  for (std::size_t p = 0; p < pinhole.mean.size(); ++p)
    worst = std::max(worst, std::fabs(focused.meanOf(p, 0) - pinhole.meanOf(p, 0)));
  CHECK(worst < 0.05);
  int previous = sharp;
  for (float aperture : {0.1f, 0.3f, 1.0f}) {
    const int blurred = blurredColumns(render(edgeScene(aperture, 1.0f)), 41);
    INFO("aperture " << aperture << ": " << blurred << " blurred columns (previous " << previous << ")");
    CHECK(blurred > previous);
    previous = blurred;
  }
}

TEST_CASE("cli: bad --max-depth, --rr-depth, aperture_radius, focus_distance, max_depth, rr_depth: one line, exit 2" * doctest::test_suite("cli sanitize")) {
  const std::string good = std::string(MONTECL_SOURCE_DIR) + "/scenes/test/good/scene.json";
  TempDir dir;
  const auto refused = [&](const std::vector<std::string>& args, const std::string& mention) {
    std::vector<std::string> argv = {"render", "-q", "-o", dir.file("out.png"), "--integrator", "path"};
    argv.insert(argv.end(), args.begin(), args.end());
    CliResult r = runMontecl(argv);
    INFO(args.back() << ": exit " << r.exitCode << ", stderr: " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(r.err.find(mention) != std::string::npos);
    CHECK(!fs::exists(dir.file("out.png")));
  };
  for (const char* v : {"0", "-2", "1.5", "x"}) refused({good, "--max-depth", v}, "--max-depth");
  for (const char* v : {"0", "-1"}) refused({good, "--rr-depth", v}, "--rr-depth");
  const std::string obj = std::string(MONTECL_SOURCE_DIR) + "/scenes/test/good/quad.obj";
  const auto sceneWith = [&](const std::string& camera, const std::string& render) {
    const std::string path = dir.file("bad.json");
    std::ofstream(path) << R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 40, "width": 8, "height": 8)"
                        << camera << R"(}, "meshes": [{"file": ")" << obj << R"("}], "render": {"integrator": "path")" << render << "}}";
    return path;
  };
  refused({sceneWith(R"(, "aperture_radius": -0.1)", "")}, "camera.aperture_radius");
  refused({sceneWith(R"(, "focus_distance": 0)", "")}, "camera.focus_distance");
  refused({sceneWith(R"(, "focus_distance": -2)", "")}, "camera.focus_distance");
  refused({sceneWith("", R"(, "max_depth": 0)")}, "render.max_depth");
  refused({sceneWith("", R"(, "max_depth": -3)")}, "render.max_depth");
  refused({sceneWith("", R"(, "rr_depth": 0)")}, "render.rr_depth");
  // And good values render.
  CliResult ok = runMontecl({"render", "-q", "-o", dir.file("ok.png"), good, "--integrator", "path", "--max-depth", "3",
                             "--rr-depth", "1", "--spp", "2", "--width", "8", "--height", "8"});
  INFO(ok.err);
  CHECK(ok.exitCode == 0);
  CHECK(fs::exists(dir.file("ok.png")));
}

// Albedo, depth and normal are the AO integrator's; the emission seen directly, which AO does not
// count on a hit, is the direct integrator's (both add Le of the camera ray's hit unweighted).
TEST_CASE("path: first-hit AOVs are those of the camera rays, identical to the AO and direct integrators'" *
          doctest::test_suite("opencl")) {
  Scene s = cornellLike(10, 3);
  RenderOptions o;
  o.aovs = true;
  o.waveSize = 41;  // several waves, each with its own bounce queues
  Film path = render(withPath(s, -1, 1), o);
  s.render.integrator = Integrator::Ao;
  Film ao = render(s, o);
  s.render.integrator = Integrator::Direct;
  Film direct = render(s, o);
  REQUIRE(path.aovSum.size() == ao.aovSum.size());
  REQUIRE(path.aovSum.size() == direct.aovSum.size());
  bool emitterSeen = false;
  for (std::size_t p = 0; p < path.count.size(); ++p) {
    const std::size_t v = MCL_AOV_VECTORS * p;
    CHECK(std::memcmp(&path.aovSum[v], &ao.aovSum[v], 2 * sizeof(glm::vec4)) == 0);
    CHECK(std::memcmp(&path.aovSum[v + 2], &direct.aovSum[v + 2], sizeof(glm::vec4)) == 0);
    emitterSeen = emitterSeen || path.aovSum[v + 2].x > 0.0f;
  }
  CHECK(emitterSeen);
}

TEST_CASE("cli: -v prints the live paths per bounce, falling from the camera rays to none" * doctest::test_suite("cli")) {
  const std::string good = std::string(MONTECL_SOURCE_DIR) + "/scenes/test/good/scene.json";
  TempDir dir;
  CliResult r = runMontecl({"render", "-v", "-q", "-o", dir.file("out.png"), good, "--integrator", "path", "--spp", "2",
                            "--rr-depth", "1"});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const std::size_t at = r.err.find("paths per bounce");
  REQUIRE(at != std::string::npos);
  std::istringstream line(r.err.substr(r.err.find("):", at) + 2));
  std::vector<unsigned long long> paths;
  std::string bounce, count, percent;
  while (line >> bounce >> count >> percent && bounce.back() == ':') paths.push_back(std::stoull(count));
  REQUIRE(paths.size() >= 2);
  CHECK(paths[0] == 32ull * 24ull * 2ull);  // every camera ray of the 32x24 image at 2 spp
  for (std::size_t b = 1; b < paths.size(); ++b) CHECK(paths[b] <= paths[b - 1]);
}

}  // namespace test_file_path
