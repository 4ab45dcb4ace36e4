// test_vs_mitsuba.cpp: the independent-renderer check, scripts/vs_mitsuba.py, through the real
// command line: montecl and Mitsuba 3 render the shared Cornell box and must agree per pixel
// (|z| > 4 on <= 0.1% of pixel channels, |mean z| <= 0.1; the script prints PASS/FAIL and exits
// 1 on FAIL); the Cornell box with material kinds (glass, rough gold, mirror: scripts/kinds_scene.py)
// per 8x8 block, and a wrong ior / metal that must fail; the same with a rough glass sphere, and the
// box lit through a rough glass pane (with a wrong ior that must fail). Skipped unless Mitsuba's venv exists (`scripts/setup.sh --mitsuba`; CI does not
// install it by default) and the shared scenes are present. The path-integrator cases also skip
// while montecl has no `--integrator path`.
#include <doctest/doctest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "skip.h"

namespace test_file_vs_mitsuba {  // keeps this file's helpers apart in a unity batch

using montecl_test::CliResult;
using montecl_test::runMontecl;
using montecl_test::runProgram;
using montecl_test::sharedScenes;

namespace {

std::string mitsubaVenvPython() {
  if (const char* v = std::getenv("MONTECL_MITSUBA_VENV")) return std::string(v) + "/bin/python";
  const char* home = std::getenv("HOME");
  return std::string(home ? home : "") + "/.cache/montecl/mitsuba-venv/bin/python";
}

bool exists(const std::string& path) { return std::ifstream(path).good(); }

CliResult runVsMitsuba(const std::vector<std::string>& extra, const std::string& scene = "") {
  std::vector<std::string> argv = {mitsubaVenvPython(), MONTECL_SOURCE_DIR "/scripts/vs_mitsuba.py",
                                   scene.empty() ? sharedScenes() + "/cornell-box/scene.json" : scene,
                                   "--montecl", MONTECL_EXE,
                                   "--width", "64", "--height", "64", "--no-timing"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  return runProgram(argv);
}

// montecl renders with --integrator path (exit 0), or refuses the choice (exit 2: not landed).
bool monteclHasPath() {
  montecl_test::TempDir dir;
  return runMontecl({"render", MONTECL_SOURCE_DIR "/scenes/demo/scene.json", "--integrator", "path", "--spp", "1",
                     "--width", "2", "--height", "2", "-q", "-o", dir.file("p.png")})
             .exitCode == 0;
}

}  // namespace

#define MCL_SKIP_UNLESS_MITSUBA()                                                                          \
  MCL_SKIP_UNLESS(exists(mitsubaVenvPython()),                                                             \
                  "no Mitsuba venv at " << mitsubaVenvPython() << " (run scripts/setup.sh --mitsuba)");    \
  MCL_SKIP_UNLESS(exists(sharedScenes() + "/cornell-box/scene.json"), "no shared scenes at " << sharedScenes())

TEST_CASE("vs_mitsuba: Cornell box, direct MIS, agrees with Mitsuba 3 per pixel" *
          doctest::test_suite("cli shared-scenes slow uninstrumented")) {
  MCL_SKIP_UNLESS_MITSUBA();
  CliResult r = runVsMitsuba({"--spp", "256", "--integrator", "direct", "--direct-sampling", "mis"});
  INFO(r.out << r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.out.find("PASS") != std::string::npos);
}

TEST_CASE("vs_mitsuba: Cornell box, path at max depth 3 and unlimited, agrees with Mitsuba 3 per pixel" *
          doctest::test_suite("cli shared-scenes slow uninstrumented")) {
  MCL_SKIP_UNLESS_MITSUBA();
  MCL_SKIP_UNLESS(monteclHasPath(), "montecl has no --integrator path yet");
  for (const char* depth : {"3", "-1"}) {
    INFO("max depth " << depth);
    CliResult r = runVsMitsuba({"--spp", "256", "--integrator", "path", "--max-depth", depth, "--rr-depth", "5"});
    INFO(r.out << r.err);
    CHECK(r.exitCode == 0);
    CHECK(r.out.find("PASS") != std::string::npos);
  }
}

TEST_CASE("vs_mitsuba: FAIL (exit 1) when montecl's red wall has albedo 0.5 instead of 0.63" *
          doctest::test_suite("cli shared-scenes slow uninstrumented")) {
  MCL_SKIP_UNLESS_MITSUBA();
  montecl_test::TempDir dir;
  const std::string box = sharedScenes() + "/cornell-box/";
  std::string mtl = montecl_test::readAll(box + "CornellBox-Original.mtl");
  const std::string red = "Kd 0.63 0.065 0.05";
  REQUIRE(mtl.find(red) != std::string::npos);
  mtl.replace(mtl.find(red), red.size(), "Kd 0.5 0.065 0.05");
  dir.write("CornellBox-Original.mtl", mtl);
  dir.write("CornellBox-Original.obj", montecl_test::readAll(box + "CornellBox-Original.obj"));
  dir.write("scene.json", montecl_test::readAll(box + "scene.json"));
  CliResult r = runVsMitsuba({"--spp", "64", "--width", "32", "--height", "32", "--integrator", "direct",
                              "--montecl-scene", dir.file("scene.json")});
  INFO(r.out << r.err);
  CHECK(r.exitCode == 1);
  CHECK(r.out.find("FAIL") != std::string::npos);
}

namespace {
// The Cornell box with a smooth glass sphere, a rough gold sphere and a mirror sphere
// (scripts/kinds_scene.py writes the spheres' OBJs and the scene into dir), optionally with extra
// kinds_scene.py arguments (a wrong ior / metal).
std::string kindsScene(const montecl_test::TempDir& dir, const std::string& sub, std::vector<std::string> extra) {
  std::vector<std::string> argv = {mitsubaVenvPython(), MONTECL_SOURCE_DIR "/scripts/kinds_scene.py", dir.file(sub),
                                   "--cornell", sharedScenes() + "/cornell-box"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  const CliResult r = runProgram(argv);
  REQUIRE_MESSAGE(r.exitCode == 0, r.err);
  return dir.file(sub) + "/scene.json";
}
// Caustics (the mirror's and the glass's on the floor) are heavy tailed: 8 x 8 block means, whose
// 192 channels' mean z has an SE of ~0.07 and a negative skew (blocks without a rare caustic path
// have a smaller mean and a smaller sample SE): the mean-z limit is 0.4 (unbiased renders gave
// -0.1 .. -0.2 at 256 - 1024 spp; the wrong ior / metal fails on |z| > 4).
const std::vector<std::string> kKindsArgs = {"--spp", "512", "--integrator", "path", "--max-depth", "3",
                                             "--block", "8", "--mean-z-limit", "0.4"};
}  // namespace

TEST_CASE("vs_mitsuba: Cornell box with glass, rough gold and mirror spheres, path depth 3, agrees per 8x8 block" *
          doctest::test_suite("cli shared-scenes slow uninstrumented")) {
  MCL_SKIP_UNLESS_MITSUBA();
  montecl_test::TempDir dir;
  CliResult r = runVsMitsuba(kKindsArgs, kindsScene(dir, "kinds", {}));
  INFO(r.out << r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.out.find("PASS") != std::string::npos);
}

TEST_CASE("vs_mitsuba: FAIL (exit 1) when montecl's glass has ior 1.3 and its gold is copper" *
          doctest::test_suite("cli shared-scenes slow uninstrumented")) {
  MCL_SKIP_UNLESS_MITSUBA();
  montecl_test::TempDir dir;
  const std::string right = kindsScene(dir, "kinds", {});
  const std::string wrong = kindsScene(dir, "wrong", {"--ior", "1.3", "--metal", "Cu"});
  std::vector<std::string> args = kKindsArgs;
  args.insert(args.end(), {"--montecl-scene", wrong});
  CliResult r = runVsMitsuba(args, right);
  INFO(r.out << r.err);
  CHECK(r.exitCode == 1);
  CHECK(r.out.find("FAIL") != std::string::npos);
}

// The rough dielectric (GGX transmission, Mitsuba's roughdielectric): the glass sphere with alpha
// 0.3; at depth 3 the light is sampled through the glass from inside the sphere (a transmitted
// light direction, its shadow ray leaving from the outside).
TEST_CASE("vs_mitsuba: Cornell box with a rough glass sphere (alpha 0.3), path depth 3, agrees per 8x8 block" *
          doctest::test_suite("cli shared-scenes slow")) {
  MCL_SKIP_UNLESS_MITSUBA();
  montecl_test::TempDir dir;
  CliResult r = runVsMitsuba(kKindsArgs, kindsScene(dir, "rough", {"--glass-alpha", "0.3"}));
  INFO(r.out << r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.out.find("PASS") != std::string::npos);
}

namespace {
// The Cornell box lit only through a rough glass pane (alpha 0.2) under its light: direct MIS per
// pixel (the light seen through the pane: next-event estimation through the transmitted lobe) and
// path depth 3 per 8x8 block (the box lit through the pane); a wrong ior must fail.
const std::vector<std::string> kPaneDirectArgs = {"--spp", "256", "--integrator", "direct", "--direct-sampling", "mis"};
}  // namespace

TEST_CASE("vs_mitsuba: Cornell box lit through a rough glass pane, direct MIS per pixel and path depth 3 per block" *
          doctest::test_suite("cli shared-scenes slow")) {
  MCL_SKIP_UNLESS_MITSUBA();
  montecl_test::TempDir dir;
  const std::string pane = kindsScene(dir, "pane", {"--pane-alpha", "0.2", "--no-spheres"});
  for (const std::vector<std::string>* args : {&kPaneDirectArgs, &kKindsArgs}) {
    CliResult r = runVsMitsuba(*args, pane);
    INFO(r.out << r.err);
    CHECK(r.exitCode == 0);
    CHECK(r.out.find("PASS") != std::string::npos);
  }
}

TEST_CASE("vs_mitsuba: FAIL (exit 1) when montecl's rough glass pane has ior 1.3" * doctest::test_suite("cli shared-scenes slow")) {
  MCL_SKIP_UNLESS_MITSUBA();
  montecl_test::TempDir dir;
  const std::string right = kindsScene(dir, "pane", {"--pane-alpha", "0.2", "--no-spheres"});
  const std::string wrong = kindsScene(dir, "wrong", {"--pane-alpha", "0.2", "--no-spheres", "--ior", "1.3"});
  std::vector<std::string> args = kPaneDirectArgs;
  args.insert(args.end(), {"--montecl-scene", wrong});
  CliResult r = runVsMitsuba(args, right);
  INFO(r.out << r.err);
  CHECK(r.exitCode == 1);
  CHECK(r.out.find("FAIL") != std::string::npos);
}

namespace {
// scripts/vs_mitsuba.py on one of scenes/test/lights/ (a floor and a box under one light), 32 x 32
// at 1024 spp against Mitsuba's 64 independent renders (4096 spp): at fewer samples montecl's
// per-pixel variance estimate is skewed with its mean in the indirect light and mean z drifts negative.
CliResult runLightsVsMitsuba(const std::string& scene, const std::vector<std::string>& extra) {
  std::vector<std::string> argv = {mitsubaVenvPython(), MONTECL_SOURCE_DIR "/scripts/vs_mitsuba.py",
                                   MONTECL_SOURCE_DIR "/scenes/test/lights/" + scene, "--montecl", MONTECL_EXE,
                                   "--no-timing", "--spp", "1024", "--ref-seeds", "64"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  return runProgram(argv);
}

}  // namespace

TEST_CASE("vs_mitsuba: point, spot and directional lights over a floor and a box agree with Mitsuba 3 per pixel "
          "(path at max depth 3; direct mis for point and spot)" *
          doctest::test_suite("cli slow uninstrumented")) {
  MCL_SKIP_UNLESS(exists(mitsubaVenvPython()),
                  "no Mitsuba venv at " << mitsubaVenvPython() << " (run scripts/setup.sh --mitsuba)");
  struct Case {
    const char* scene;
    std::vector<std::string> args;
  };
  const std::vector<std::string> path = {"--integrator", "path", "--max-depth", "3"};
  const std::vector<std::string> direct = {"--integrator", "direct", "--direct-sampling", "mis"};
  for (const Case& c : {Case{"point.json", path}, Case{"spot.json", path}, Case{"directional.json", path},
                        Case{"point.json", direct}, Case{"spot.json", direct}}) {
    CliResult r = runLightsVsMitsuba(c.scene, c.args);
    INFO(c.scene << " " << c.args[1] << ": " << r.out << r.err);
    CHECK(r.exitCode == 0);
    CHECK(r.out.find("PASS") != std::string::npos);
  }
}

TEST_CASE("vs_mitsuba: FAIL (exit 1) when montecl's point light is 5% too bright" * doctest::test_suite("cli slow uninstrumented")) {
  MCL_SKIP_UNLESS(exists(mitsubaVenvPython()),
                  "no Mitsuba venv at " << mitsubaVenvPython() << " (run scripts/setup.sh --mitsuba)");
  montecl_test::TempDir dir;
  std::string scene = montecl_test::readAll(MONTECL_SOURCE_DIR "/scenes/test/lights/point.json");
  const std::string intensity = "\"intensity\": [\n    3,\n    2.5,\n    2\n   ]";
  REQUIRE(scene.find(intensity) != std::string::npos);
  scene.replace(scene.find(intensity), intensity.size(), "\"intensity\": [3.15, 2.625, 2.1]");
  dir.write("point.json", scene);
  dir.write("floor-box.obj", montecl_test::readAll(MONTECL_SOURCE_DIR "/scenes/test/lights/floor-box.obj"));
  CliResult r = runLightsVsMitsuba("point.json", {"--integrator", "direct", "--montecl-scene", dir.file("point.json")});
  INFO(r.out << r.err);
  CHECK(r.exitCode == 1);
  CHECK(r.out.find("FAIL") != std::string::npos);
}

namespace {
// The sun (a disk of angular diameter "angle", sampled by solid angle) against Mitsuba's stand-in:
// a black disk 1e4 units away with a one-sided area emitter of the same radiance and cone
// (scripts/vs_mitsuba.py). Under direct lighting most lit pixels have a tiny sample variance (only
// the cosine varies across the cone), so the stand-in's 4e-4 offset in the image mean (its finite
// distance and float precision) moves their z: mean-z limit 0.25 there; per pixel otherwise.
const std::vector<std::string> kSunDirect = {"--integrator", "direct", "--direct-sampling", "mis", "--mean-z-limit", "0.25"};
const std::vector<std::string> kPath3 = {"--integrator", "path", "--max-depth", "3"};
const std::vector<std::string> kPathAll = {"--integrator", "path", "--max-depth", "-1"};

// A quad whose emission texture (glow.png, black but for an off-centre block) lights the floor and
// box: next-event estimation picks points uniformly on the emitting triangles, 90% of them on black
// texels, so the samples are heavy tailed: 4096 spp, 4 x 4 block means with the mean-z limit of
// the other heavy-tailed comparisons (unbiased renders gave -0.29 .. +0.20 over three seeds).
CliResult runEmissiveVsMitsuba(const std::vector<std::string>& integrator, const std::string& montecl_scene = "") {
  std::vector<std::string> args = {"--spp", "4096", "--block", "4", "--mean-z-limit", "0.4"};
  args.insert(args.end(), integrator.begin(), integrator.end());
  if (!montecl_scene.empty()) args.insert(args.end(), {"--montecl-scene", montecl_scene});
  return runLightsVsMitsuba("emissive-texture.json", args);
}
}  // namespace

TEST_CASE("vs_mitsuba: a sun disk and an emission texture agree with Mitsuba 3 (direct, path at max depth 3 and unlimited)" *
          doctest::test_suite("cli slow uninstrumented")) {
  MCL_SKIP_UNLESS(exists(mitsubaVenvPython()),
                  "no Mitsuba venv at " << mitsubaVenvPython() << " (run scripts/setup.sh --mitsuba)");
  for (const std::vector<std::string>* args : {&kSunDirect, &kPath3, &kPathAll}) {
    CliResult r = runLightsVsMitsuba("sun.json", *args);
    INFO("sun " << (*args)[1] << ": " << r.out << r.err);
    CHECK(r.exitCode == 0);
    CHECK(r.out.find("PASS") != std::string::npos);
  }
  const std::vector<std::string> direct = {"--integrator", "direct", "--direct-sampling", "mis"};
  for (const std::vector<std::string>* args : {&direct, &kPath3, &kPathAll}) {
    CliResult r = runEmissiveVsMitsuba(*args);
    INFO("emission texture " << (*args)[1] << ": " << r.out << r.err);
    CHECK(r.exitCode == 0);
    CHECK(r.out.find("PASS") != std::string::npos);
  }
}

TEST_CASE("vs_mitsuba: FAIL (exit 1) when montecl's sun is half as wide and its emission texture is mirrored" *
          doctest::test_suite("cli slow uninstrumented")) {
  MCL_SKIP_UNLESS(exists(mitsubaVenvPython()),
                  "no Mitsuba venv at " << mitsubaVenvPython() << " (run scripts/setup.sh --mitsuba)");
  montecl_test::TempDir dir;
  const std::string lights = MONTECL_SOURCE_DIR "/scenes/test/lights/";
  for (const char* f : {"floor-box.obj", "glow.png", "glow-quad.mtl", "emissive-texture.json"})
    dir.write(f, montecl_test::readAll(lights + f));
  std::string sun = montecl_test::readAll(lights + "sun.json");
  const std::string angle = "\"angle\": 20";
  REQUIRE(sun.find(angle) != std::string::npos);
  sun.replace(sun.find(angle), angle.size(), "\"angle\": 10");
  dir.write("sun.json", sun);
  std::string quad = montecl_test::readAll(lights + "glow-quad.obj");
  const std::string uvs = "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
  REQUIRE(quad.find(uvs) != std::string::npos);
  quad.replace(quad.find(uvs), uvs.size(), "vt 1 0\nvt 0 0\nvt 0 1\nvt 1 1\n");  // u -> 1 - u
  dir.write("glow-quad.obj", quad);
  CliResult r = runLightsVsMitsuba("sun.json", {"--integrator", "path", "--max-depth", "3", "--montecl-scene", dir.file("sun.json")});
  INFO(r.out << r.err);
  CHECK(r.exitCode == 1);
  CHECK(r.out.find("FAIL") != std::string::npos);
  r = runEmissiveVsMitsuba({"--integrator", "direct"}, dir.file("emissive-texture.json"));
  INFO(r.out << r.err);
  CHECK(r.exitCode == 1);
  CHECK(r.out.find("FAIL") != std::string::npos);
}

namespace {
// A Mitsuba scene of built-in shapes montecl builds exactly (rectangles, a cube: flat faces): a
// floor, a block, and a light facing down, seen from the front; `light` its radiance.
std::string builtinXml(const std::string& light) {
  return "<scene version=\"3.0.0\">\n"
         "<sensor type=\"perspective\"><float name=\"fov\" value=\"45\"/><transform name=\"to_world\">"
         "<lookat origin=\"0 2 5\" target=\"0 0.5 0\" up=\"0 1 0\"/></transform></sensor>\n"
         "<bsdf type=\"twosided\" id=\"grey\"><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.6 0.5 0.4\"/></bsdf></bsdf>\n"
         "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"3\"/><rotate x=\"1\" angle=\"-90\"/></transform>"
         "<ref id=\"grey\"/></shape>\n"
         "<shape type=\"cube\"><transform name=\"to_world\"><scale value=\"0.5\"/><rotate y=\"1\" angle=\"30\"/>"
         "<translate y=\"0.5\"/></transform><ref id=\"grey\"/></shape>\n"
         "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"0.5\"/><rotate x=\"1\" angle=\"90\"/>"
         "<translate y=\"2.5\"/></transform><emitter type=\"area\"><rgb name=\"radiance\" value=\"" + light + "\"/></emitter></shape>\n"
         "</scene>\n";
}
}  // namespace

TEST_CASE("vs_mitsuba: a Mitsuba XML scene goes to Mitsuba as it is and agrees per pixel; a brighter light in montecl's copy fails" *
          doctest::test_suite("cli slow uninstrumented")) {
  MCL_SKIP_UNLESS(exists(mitsubaVenvPython()), "no Mitsuba venv at " << mitsubaVenvPython() << " (run scripts/setup.sh --mitsuba)");
  montecl_test::TempDir dir;
  dir.write("scene.xml", builtinXml("8 8 8"));
  dir.write("brighter.xml", builtinXml("8.8 8.8 8.8"));
  const std::vector<std::string> args = {"--spp", "256", "--integrator", "path", "--max-depth", "3"};
  CliResult r = runVsMitsuba(args, dir.file("scene.xml"));
  INFO(r.out << r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.out.find("PASS") != std::string::npos);
  std::vector<std::string> wrong = args;
  wrong.insert(wrong.end(), {"--montecl-scene", dir.file("brighter.xml")});
  r = runVsMitsuba(wrong, dir.file("scene.xml"));
  CHECK(r.exitCode == 1);
  CHECK(r.out.find("FAIL") != std::string::npos);
}

}  // namespace test_file_vs_mitsuba
