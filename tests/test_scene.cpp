// test_scene.cpp: unit tests of loadScene()/loadObjInto()/defaultCamera(): values parsed from scene
// files, OBJ/MTL materials, degenerate triangles, emission overrides, default framing of bare OBJs,
// every bad-input case under scenes/test/bad/ (one InputError line naming file and key/line), and
// loading of the shared scenes (skipped when ../shared/scenes is absent).
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>
#include <grp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "cli_runner.h"
#include "scene/scene.h"
#include "util/errors.h"
#include "skip.h"

namespace test_file_scene {  // keeps this file's helpers apart in a unity batch

using montecl::Camera;
using montecl::InputError;
using montecl::Scene;
using montecl_test::TempDir;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kBadCases = std::string(MONTECL_SOURCE_DIR) + "/scenes/test/bad";

json baseScene(const std::string& meshFile) {
  return json{{"camera",
               {{"position", {0, 0, 3}}, {"target", {0, 0, 0}}, {"fov_y", 45}, {"width", 64}, {"height", 48}}},
              {"meshes", json::array({json{{"file", meshFile}}})}};
}

const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

Scene load(const std::string& path) {
  std::vector<std::string> warnings;
  return montecl::loadScene(path, warnings);
}

// The InputError message of loading path ("" when it loads).
std::string loadError(const std::string& path) {
  try {
    load(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// loadError of each path in a forked child that is not root (it drops to the user nobody when
// run as root, so file permissions apply); failure says why the child could not run.
struct UnprivilegedLoad {
  std::vector<std::string> messages;
  std::string failure;
};
UnprivilegedLoad loadErrorsUnprivileged(const std::vector<std::string>& paths) {
  UnprivilegedLoad out;
  int fds[2];
  if (::pipe(fds) != 0) {
    out.failure = "pipe failed";
    return out;
  }
  pid_t pid = ::fork();
  if (pid == 0) {  // child: no doctest macros here
    ::close(fds[0]);
    std::string reply;
    if (::geteuid() == 0 && (::setgroups(0, nullptr) != 0 || ::setgid(65534) != 0 || ::setuid(65534) != 0))
      reply = std::string("!cannot drop root: ") + std::strerror(errno);
    else if (::geteuid() == 0)
      reply = "!still root";
    else
      for (const std::string& p : paths) reply += loadError(p) + '\n';
    ssize_t unused = ::write(fds[1], reply.data(), reply.size());
    (void)unused;
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string reply;
  char buf[4096];
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) reply.append(buf, std::size_t(n));
  ::close(fds[0]);
  int status = 0;
  if (pid < 0 || ::waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    out.failure = "child process failed";
  else if (!reply.empty() && reply[0] == '!')
    out.failure = reply.substr(1);
  else
    for (std::size_t a = 0, b; (b = reply.find('\n', a)) != std::string::npos; a = b + 1)
      out.messages.push_back(reply.substr(a, b - a));
  return out;
}

// Pixel coordinates of p seen through cam (pinhole, fovY vertical); z <= 0 means behind it.
glm::dvec3 project(const Camera& cam, const glm::vec3& p) {
  glm::dvec3 f = glm::normalize(glm::dvec3(cam.target - cam.position));
  glm::dvec3 r = glm::normalize(glm::cross(f, glm::dvec3(cam.up)));
  glm::dvec3 u = glm::cross(r, f);
  glm::dvec3 d = glm::dvec3(p - cam.position);
  double z = glm::dot(d, f);
  double tanY = std::tan(glm::radians(double(cam.fovY)) / 2), aspect = double(cam.width) / cam.height;
  double x = glm::dot(d, r) / z / (tanY * aspect), y = glm::dot(d, u) / z / tanY;
  return {(x * 0.5 + 0.5) * cam.width, (0.5 - y * 0.5) * cam.height, z};
}

std::vector<glm::vec3> corners(const glm::vec3& lo, const glm::vec3& hi) {
  std::vector<glm::vec3> c;
  for (int i = 0; i < 8; ++i) c.emplace_back(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
  return c;
}

// Every corner inside the image, and the box not lost in the middle of it (spans >= 40%).
void checkFramed(const Camera& cam, const glm::vec3& lo, const glm::vec3& hi) {
  double minX = 1e30, maxX = -1e30, minY = 1e30, maxY = -1e30;
  for (const glm::vec3& c : corners(lo, hi)) {
    glm::dvec3 px = project(cam, c);
    CHECK(px.z > 0);
    CHECK(px.x >= 0);
    CHECK(px.x <= cam.width);
    CHECK(px.y >= 0);
    CHECK(px.y <= cam.height);
    minX = std::min(minX, px.x), maxX = std::max(maxX, px.x);
    minY = std::min(minY, px.y), maxY = std::max(maxY, px.y);
  }
  CHECK(std::max((maxX - minX) / cam.width, (maxY - minY) / cam.height) > 0.4);
}

const montecl::MaterialDesc& materialOf(const Scene& s, std::size_t tri) {
  return s.materials.at(s.triangles.at(tri).material);
}

bool containsWarning(const std::vector<std::string>& warnings, const std::string& a, const std::string& b) {
  return std::any_of(warnings.begin(), warnings.end(), [&](const std::string& w) {
    return w.find(a) != std::string::npos && w.find(b) != std::string::npos;
  });
}

}  // namespace

TEST_CASE("scene file: every camera and render value is parsed" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("tri.obj", kTriangleObj);
  json s = baseScene("tri.obj");
  s["camera"] = {{"position", {1, 2, 3}}, {"target", {0.5, -1, 0.25}}, {"up", {0, 0, 1}},
                 {"fov_y", 33.5}, {"width", 320}, {"height", 200}};
  s["render"] = {{"integrator", "direct"}, {"spp", 7},        {"seed", 4000000000u},
                 {"ao_distance", 2.5},     {"ao_sampling", "uniform"}, {"background", {0.1, 0.2, 0.3}},
                 {"direct_sampling", "brdf"}, {"light_samples", 3}};
  dir.write("scene.json", s.dump());
  std::vector<std::string> warnings;
  Scene scene = montecl::loadScene(dir.file("scene.json"), warnings);
  CHECK(warnings.empty());
  CHECK(scene.path == dir.file("scene.json"));
  CHECK(scene.camera.position == glm::vec3(1, 2, 3));
  CHECK(scene.camera.target == glm::vec3(0.5f, -1.0f, 0.25f));
  CHECK(scene.camera.up == glm::vec3(0, 0, 1));
  CHECK(scene.camera.fovY == doctest::Approx(33.5));
  CHECK(scene.camera.width == 320);
  CHECK(scene.camera.height == 200);
  CHECK(scene.render.integrator == montecl::Integrator::Direct);
  CHECK(scene.render.spp == 7);
  CHECK(scene.render.seed == 4000000000u);
  CHECK(scene.render.aoDistance == doctest::Approx(2.5));
  CHECK(scene.render.aoSampling == montecl::AoSampling::Uniform);
  CHECK(scene.render.background == glm::vec3(0.1f, 0.2f, 0.3f));
  CHECK(scene.render.directSampling == montecl::DirectSampling::Brdf);
  CHECK(scene.render.lightSamples == 3);
  REQUIRE(scene.triangles.size() == 1);
  CHECK(scene.boundsMin == glm::vec3(0, 0, 0));
  CHECK(scene.boundsMax == glm::vec3(1, 1, 0));
}

TEST_CASE("scene file: up and render are optional with the documented defaults" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("tri.obj", kTriangleObj);
  dir.write("scene.json", baseScene("tri.obj").dump());
  Scene scene = load(dir.file("scene.json"));
  montecl::RenderSettings defaults;
  CHECK(scene.camera.up == glm::vec3(0, 1, 0));
  CHECK(scene.render.integrator == defaults.integrator);
  CHECK(scene.render.spp == defaults.spp);
  CHECK(scene.render.seed == defaults.seed);
  CHECK(scene.render.aoDistance == defaults.aoDistance);
  CHECK(scene.render.aoSampling == defaults.aoSampling);
  CHECK(scene.render.background == defaults.background);
  CHECK(scene.render.directSampling == montecl::DirectSampling::Mis);
  CHECK(scene.render.lightSamples == 1);
}

TEST_CASE("scene file: mesh paths are relative to the scene file's folder" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("meshes/far.obj", "v 5 0 0\nv 6 0 0\nv 5 1 0\nf 1 2 3\n");
  dir.write("scenes/a/sub/near.obj", "v 0 0 -2\nv 1 0 -2\nv 0 1 -2\nf 1 2 3\n");
  json s = baseScene("../../meshes/far.obj");
  s["meshes"].push_back(json{{"file", "sub/near.obj"}});
  dir.write("scenes/a/scene.json", s.dump());
  REQUIRE(fs::current_path() != fs::path(dir.file("scenes/a")));
  Scene scene = load(dir.file("scenes/a/scene.json"));
  REQUIRE(scene.triangles.size() == 2);
  CHECK(scene.triangles[0].v[0] == glm::vec3(5, 0, 0));
  CHECK(scene.triangles[1].v[0] == glm::vec3(0, 0, -2));
  CHECK(scene.boundsMin == glm::vec3(0, 0, -2));
  CHECK(scene.boundsMax == glm::vec3(6, 1, 0));
}

TEST_CASE("OBJ: MTL Kd and Ke are read, and each OBJ's materials get their own indices" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("a.mtl", "newmtl paint\nKd 0.1 0.2 0.3\n\nnewmtl lamp\nKd 0 0 0\nKe 4 5 6\n");
  dir.write("a.obj", "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl paint\nf 1 2 3\nusemtl lamp\nf 1 3 2\n");
  dir.write("b.mtl", "newmtl paint\nKd 0.9 0.8 0.7\n");
  dir.write("b.obj", "mtllib b.mtl\nusemtl paint\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 1 2 3\n");
  json s = baseScene("a.obj");
  s["meshes"].push_back(json{{"file", "b.obj"}});
  dir.write("scene.json", s.dump());
  Scene scene = load(dir.file("scene.json"));
  REQUIRE(scene.triangles.size() == 3);
  CHECK(materialOf(scene, 0).albedo == glm::vec3(0.1f, 0.2f, 0.3f));
  CHECK(materialOf(scene, 0).emission == glm::vec3(0.0f));
  CHECK(materialOf(scene, 1).albedo == glm::vec3(0.0f));
  CHECK(materialOf(scene, 1).emission == glm::vec3(4, 5, 6));
  CHECK(materialOf(scene, 2).albedo == glm::vec3(0.9f, 0.8f, 0.7f));
  CHECK(scene.triangles[0].material != scene.triangles[2].material);  // both named "paint"
  std::set<std::uint32_t> distinct;
  for (const auto& t : scene.triangles) distinct.insert(t.material);
  CHECK(distinct.size() == 3);
}

TEST_CASE("OBJ: faces without a material share one 0.5 grey default material" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("plain.obj", kTriangleObj);
  dir.write("mixed.mtl", "newmtl red\nKd 1 0 0\n");
  dir.write("mixed.obj", "mtllib mixed.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl red\nf 1 3 2\n");
  json s = baseScene("plain.obj");
  s["meshes"].push_back(json{{"file", "mixed.obj"}});
  dir.write("scene.json", s.dump());
  Scene scene = load(dir.file("scene.json"));
  REQUIRE(scene.triangles.size() == 3);
  CHECK(materialOf(scene, 0).albedo == glm::vec3(0.5f));
  CHECK(materialOf(scene, 0).emission == glm::vec3(0.0f));
  CHECK(scene.triangles[1].material == scene.triangles[0].material);
  CHECK(materialOf(scene, 2).albedo == glm::vec3(1, 0, 0));
  CHECK(montecl::defaultMaterialIndex(scene) == scene.triangles[0].material);
}

TEST_CASE("OBJ: quads and polygons are triangulated, negative indices resolved" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("poly.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"
            "v 0 0 1\nv 2 0 1\nv 3 1 1\nv 1 2 1\nv -1 1 1\nf -5 -4 -3 -2 -1\n"
            "f 1/1/1 2//2 3/3\n");
  std::vector<std::string> warnings;
  Scene scene = montecl::loadScene(dir.file("poly.obj"), warnings);
  CHECK(scene.triangles.size() == 2 + 3 + 1);
  CHECK(scene.boundsMin == glm::vec3(-1, 0, 0));
  CHECK(scene.boundsMax == glm::vec3(3, 2, 1));
  // Winding is kept: every triangle of these counter-clockwise polygons faces +z.
  for (const auto& t : scene.triangles) CHECK(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]).z > 0);
}

TEST_CASE("OBJ: CRLF line ends, a byte order mark, tabs and comments are accepted" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("dos.obj", "\xEF\xBB\xBFv 0 0 0\r\n# comment\r\n\tv\t1 0 0\r\nv 0 1 0 1.0\r\n\r\nf 1 2 3\r\n");
  std::vector<std::string> warnings;
  Scene scene = montecl::loadScene(dir.file("dos.obj"), warnings);
  CHECK(warnings.empty());
  REQUIRE(scene.triangles.size() == 1);
  CHECK(scene.triangles[0].v[0] == glm::vec3(0, 0, 0));
  CHECK(scene.triangles[0].v[1] == glm::vec3(1, 0, 0));
  CHECK(scene.triangles[0].v[2] == glm::vec3(0, 1, 0));
}

TEST_CASE("OBJ: degenerate triangles are dropped and counted, and do not grow the bounds" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("degenerate.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 100 100 100\nv 200 200 200\nv 300 300 300\n"
            "f 1 2 3\n"     // kept
            "f 4 5 6\n"     // collinear, far away
            "f 1 1 2\n"     // repeated vertex
            "f 2 3 1\n");   // kept
  Scene scene = load(dir.file("degenerate.obj"));
  CHECK(scene.triangles.size() == 2);
  CHECK(scene.degenerateDropped == 2);
  CHECK(scene.boundsMin == glm::vec3(0, 0, 0));
  CHECK(scene.boundsMax == glm::vec3(1, 1, 0));
}

TEST_CASE("scene file: a mesh's emission makes all its triangles emitters" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("lamp.mtl", "newmtl shade\nKd 0.2 0.3 0.4\n");
  dir.write("lamp.obj", "mtllib lamp.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl shade\nf 1 2 3\n");
  dir.write("plain.obj", kTriangleObj);
  json s = baseScene("lamp.obj");
  s["meshes"][0]["emission"] = {1, 2, 3};
  s["meshes"].push_back(json{{"file", "plain.obj"}, {"emission", {7, 8, 9}}});
  s["meshes"].push_back(json{{"file", "plain.obj"}});
  dir.write("scene.json", s.dump());
  Scene scene = load(dir.file("scene.json"));
  REQUIRE(scene.triangles.size() == 3);
  CHECK(materialOf(scene, 0).albedo == glm::vec3(0.2f, 0.3f, 0.4f));
  CHECK(materialOf(scene, 0).emission == glm::vec3(1, 2, 3));
  CHECK(materialOf(scene, 1).albedo == glm::vec3(0.5f));
  CHECK(materialOf(scene, 1).emission == glm::vec3(7, 8, 9));
  CHECK(materialOf(scene, 2).albedo == glm::vec3(0.5f));       // the shared default stays
  CHECK(materialOf(scene, 2).emission == glm::vec3(0.0f));     // non-emissive
}

TEST_CASE("bare OBJ: default camera and render settings, camera frames the bounding box" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("Shape.OBJ", "v -3 10 2\nv 5 10 2\nv 5 14 -7\nf 1 2 3\n");
  Scene scene = load(dir.file("Shape.OBJ"));
  CHECK(scene.path == dir.file("Shape.OBJ"));
  CHECK(scene.camera.width == 512);
  CHECK(scene.camera.height == 512);
  CHECK(scene.render.spp == montecl::RenderSettings{}.spp);
  CHECK(scene.boundsMin == glm::vec3(-3, 10, -7));
  CHECK(scene.boundsMax == glm::vec3(5, 14, 2));
  checkFramed(scene.camera, scene.boundsMin, scene.boundsMax);
  // Nothing in it emits: path-traced under the default white sky.
  CHECK(scene.render.integrator == montecl::Integrator::Path);
  CHECK(scene.environment.enabled);
  CHECK(scene.environment.file.empty());
  CHECK(scene.environment.radiance * scene.environment.scale == glm::vec3(montecl::kDefaultSkyRadiance));
}

TEST_CASE("bare OBJ with an emitter: path-traced by its own light under a dimmer default sky" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("lamp.mtl", "newmtl lamp\nKe 4 4 4\n");
  dir.write("lamp.obj", "mtllib lamp.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 -1\nv 1 0 -1\nv 0 1 -1\n"
                        "f 1 2 3\nusemtl lamp\nf 4 5 6\n");
  Scene scene = load(dir.file("lamp.obj"));
  CHECK(scene.render.integrator == montecl::Integrator::Path);
  // The model's lights keep a sky, dimmer than a model without lights gets, so they still read.
  CHECK(scene.environment.enabled);
  CHECK(scene.environment.file.empty());
  CHECK(scene.environment.radiance * scene.environment.scale == glm::vec3(montecl::kLitModelSkyRadiance));
  CHECK(scene.defaultsNote.find("--env none") != std::string::npos);
}

TEST_CASE("scene file camera: \"auto\" and missing keys come from the automatic framing" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("tri.obj", "v -3 10 2\nv 5 10 2\nv 5 14 -7\nf 1 2 3\n");
  const auto sceneWith = [&](const std::string& camera) {
    dir.write("scene.json", "{\"camera\": " + camera + ", \"meshes\": [{\"file\": \"tri.obj\"}]}");
    return load(dir.file("scene.json"));
  };
  const glm::vec3 lo(-3, 10, -7), hi(5, 14, 2);
  const Camera front = montecl::defaultCamera(lo, hi, 512, 512);
  const Camera wide = montecl::defaultCamera(lo, hi, 24, 16);
  const auto same = [](const Camera& a, const Camera& b) {
    CHECK(a.position == b.position);
    CHECK(a.target == b.target);
    CHECK(a.up == b.up);
    CHECK(a.fovY == b.fovY);
    CHECK(a.width == b.width);
    CHECK(a.height == b.height);
  };
  same(sceneWith("\"auto\"").camera, front);
  same(sceneWith("{}").camera, front);
  same(sceneWith(R"({"width": 24, "height": 16})").camera, wide);
  // Given keys win; the rest is still the framing (for the given image size).
  Camera c = sceneWith(R"({"position": [0, 30, 40], "fov_y": 25, "width": 24, "height": 16})").camera;
  CHECK(c.position == glm::vec3(0, 30, 40));
  CHECK(c.fovY == 25.0f);
  CHECK(c.target == wide.target);
  // A scene file's integrator stays its own: the bare-model defaults are for bare models only.
  CHECK(sceneWith("\"auto\"").render.integrator == montecl::RenderSettings{}.integrator);
  CHECK_FALSE(sceneWith("\"auto\"").environment.enabled);
  // Any other string is one line naming the key.
  try {
    sceneWith("\"front\"");
    FAIL("expected an InputError");
  } catch (const montecl::InputError& e) {
    CHECK(std::string(e.what()).find(dir.file("scene.json") + ": camera: expected an object or \"auto\"") == 0);
  }
}

TEST_CASE("defaultCamera frames boxes of any shape for any aspect ratio" * doctest::test_suite("cpu")) {
  const std::vector<std::pair<glm::vec3, glm::vec3>> boxes = {
      {{-1, -1, -1}, {1, 1, 1}},     {{0, 0, 0}, {100, 1, 1}},      {{0, 0, 0}, {1, 100, 1}},
      {{0, 0, 0}, {1, 1, 100}},      {{1000, 2000, -500}, {1001, 2000.5f, -499}}, {{0, 0, 0}, {1e-3f, 2e-3f, 0}}};
  const std::vector<std::pair<int, int>> sizes = {{512, 512}, {800, 200}, {200, 800}};
  for (const auto& box : boxes) {
    const glm::vec3& lo = box.first;
    const glm::vec3& hi = box.second;
    for (const auto& row : sizes) {
      const auto& w = std::get<0>(row);
      const auto& h = std::get<1>(row);
      INFO("box " << lo.x << "," << lo.y << "," << lo.z << " .. " << hi.x << "," << hi.y << "," << hi.z
                  << " image " << w << "x" << h);
      Camera cam = montecl::defaultCamera(lo, hi, w, h);
      CHECK(cam.width == w);
      CHECK(cam.height == h);
      CHECK(cam.fovY > 0);
      CHECK(cam.fovY < 180);
      CHECK(cam.position.z > cam.target.z);  // seen from the +z side
      CHECK(cam.position.y > cam.target.y);  // tilted down
      checkFramed(cam, lo, hi);
    }
  }
}

TEST_CASE("scene file: unknown keys are warnings naming the file and the key" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("tri.obj", kTriangleObj);
  json s = baseScene("tri.obj");
  s["comment"] = "hi";
  s["camera"]["aperture"] = 0.1;
  s["render"] = {{"spp", 2}, {"max_bounces", 5}};
  s["meshes"][0]["scale"] = 2;
  dir.write("scene.json", s.dump());
  std::vector<std::string> warnings;
  Scene scene = montecl::loadScene(dir.file("scene.json"), warnings);
  CHECK(scene.render.spp == 2);
  CHECK(warnings.size() == 4);
  for (const char* key : {"comment", "camera.aperture", "render.max_bounces", "meshes[0].scale"}) {
    INFO(key);
    CHECK(containsWarning(warnings, dir.file("scene.json") + ": " + key, "unknown key"));
  }
}

TEST_CASE("OBJ: missing MTL and unknown statements are warnings, not errors" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("m.obj", "mtllib nowhere.mtl\nusemtl stone\nv 0 0 0\nv 1 0 0\nfrobnicate 3\nv 0 1 0\nf 1 2 3\n");
  std::vector<std::string> warnings;
  Scene scene = montecl::loadScene(dir.file("m.obj"), warnings);
  REQUIRE(scene.triangles.size() == 1);
  CHECK(materialOf(scene, 0).albedo == glm::vec3(0.5f));
  CHECK(containsWarning(warnings, "m.obj", "nowhere.mtl"));
  CHECK(containsWarning(warnings, "line 5", "frobnicate"));
  dir.write("n.mtl", "newmtl brick\nKd 0.3 0.2 0.1\n");
  dir.write("n.obj", "mtllib n.mtl\nusemtl marble\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  warnings.clear();
  scene = montecl::loadScene(dir.file("n.obj"), warnings);
  REQUIRE(scene.triangles.size() == 1);
  CHECK(materialOf(scene, 0).albedo == glm::vec3(0.5f));
  CHECK(containsWarning(warnings, "n.obj", "marble"));
  for (const std::string& w : warnings) CHECK(w.find('\n') == std::string::npos);
}

TEST_CASE("bad input: every case under scenes/test/bad throws one InputError line naming file and key" * doctest::test_suite("cpu")) {
  std::vector<fs::path> cases;
  for (const auto& entry : fs::directory_iterator(kBadCases)) cases.push_back(entry.path());
  std::sort(cases.begin(), cases.end());
  REQUIRE(cases.size() >= 40);
  for (const fs::path& dir : cases) {
    std::vector<std::string> expect = montecl_test::readLines((dir / "expect.txt").string());
    REQUIRE(expect.size() >= 2);
    std::string path = (dir / expect[0]).string();
    std::string message = loadError(path);
    INFO("case " << dir.filename().string() << ": " << message);
    CHECK(!message.empty());
    CHECK(message.find('\n') == std::string::npos);
    for (std::size_t i = 1; i < expect.size(); ++i) CHECK(message.find(expect[i]) != std::string::npos);
  }
}

TEST_CASE("bad input: missing and unreadable files name the file" * doctest::test_suite("cpu")) {
  TempDir dir;
  std::string message = loadError(dir.file("no-such-scene.json"));
  CHECK(message.find("no-such-scene.json") != std::string::npos);
  CHECK(message.find("No such file") != std::string::npos);
  message = loadError(dir.file("no-such-mesh.obj"));
  CHECK(message.find("no-such-mesh.obj") != std::string::npos);
  CHECK(loadError(dir.path).find("directory") != std::string::npos);
  // A file with no permissions, in a folder anyone may enter, read by an unprivileged process:
  // under root (as CI runs) a child process drops to the user nobody first, since root reads
  // any file. A readable scene beside it must load in that same process.
  dir.write("tri.obj", kTriangleObj);
  dir.write("open.json", baseScene("tri.obj").dump());
  dir.write("locked.json", baseScene("tri.obj").dump());
  fs::permissions(dir.path, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                fs::perms::others_read | fs::perms::others_exec);
  fs::permissions(dir.file("locked.json"), fs::perms::none);
  UnprivilegedLoad r = loadErrorsUnprivileged({dir.file("open.json"), dir.file("locked.json")});
  INFO("child: " << r.failure);
  REQUIRE(r.failure.empty());
  REQUIRE(r.messages.size() == 2);
  CHECK(r.messages[0] == "");
  message = r.messages[1];
  CHECK(message.find("locked.json") != std::string::npos);
  CHECK(message.find("Permission denied") != std::string::npos);
}

TEST_CASE("demo scene: loads without warnings and has an emitter" * doctest::test_suite("cpu")) {
  std::vector<std::string> warnings;
  Scene scene = montecl::loadScene(std::string(MONTECL_SOURCE_DIR) + "/scenes/demo/scene.json", warnings);
  CHECK(warnings.empty());
  CHECK(scene.triangles.size() > 1000);
  CHECK(scene.triangles.size() < 10000);
  CHECK(scene.degenerateDropped == 0);
  std::size_t emitters = 0;
  for (const auto& t : scene.triangles) emitters += glm::length(scene.materials[t.material].emission) > 0;
  CHECK(emitters == 2);  // the light quad
}

TEST_CASE("shared scenes: all load, fast enough to report" * doctest::test_suite("cpu shared-scenes")) {
  const fs::path root = montecl_test::sharedScenes();
  MCL_SKIP_UNLESS(fs::is_directory(root), root.string() << " not found (the shared scenes are not beside this checkout)");
  int loaded = 0;
  for (const char* name : {"cornell-box", "bunny", "sibenik", "sponza"}) {
    fs::path file = root / name / "scene.json";
    if (!fs::exists(file)) {
      MESSAGE("shared scene skipping: " << file.string() << " not found");
      continue;
    }
    auto start = std::chrono::steady_clock::now();
    std::vector<std::string> warnings;
    Scene scene = montecl::loadScene(file.string(), warnings);
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    MESSAGE(std::string(name) << ": " << scene.triangles.size() << " triangles, " << scene.degenerateDropped
                 << " degenerate dropped, " << scene.materials.size() << " materials, loaded in " << ms << " ms");
    INFO(std::string(name));
    // Only the MTL statements montecl does not use (Cornell box: Ka, Ni, illum), one line per kind.
    for (const std::string& w : warnings) {
      INFO(w);
      CHECK(w.find("not used by montecl") != std::string::npos);
    }
    CHECK(warnings.size() <= 8);
    CHECK(scene.triangles.size() > 30);
    std::size_t emitters = 0;
    for (const auto& t : scene.triangles) emitters += glm::length(scene.materials[t.material].emission) > 0;
    CHECK(emitters > 0);
    ++loaded;
  }
  CHECK(loaded > 0);
}

TEST_CASE("emittersFaceAnything: false only when every emitter's emitting side faces away from all geometry" * doctest::test_suite("cpu")) {
  using namespace montecl;
  Scene s;
  s.materials = {MaterialDesc{"floor", glm::vec3(0.5f), glm::vec3(0.0f)}, MaterialDesc{"light", glm::vec3(0.0f), glm::vec3(1.0f)}};
  s.triangles.push_back({{{-1, 0, -1}, {1, 0, -1}, {0, 0, 1}}, 0});  // floor at y = 0
  // Light at y = 1 wound so that cross(v1 - v0, v2 - v0) points up (+y): away from the floor.
  s.triangles.push_back({{{-1, 1, -1}, {0, 1, 1}, {1, 1, -1}}, 1});
  REQUIRE(glm::cross(s.triangles[1].v[1] - s.triangles[1].v[0], s.triangles[1].v[2] - s.triangles[1].v[0]).y > 0);
  CHECK_FALSE(emittersFaceAnything(s));
  s.materials[1].twoSidedEmission = true;
  CHECK(emittersFaceAnything(s));
  s.materials[1].twoSidedEmission = false;
  std::swap(s.triangles[1].v[1], s.triangles[1].v[2]);  // now facing down, toward the floor
  CHECK(emittersFaceAnything(s));
}

TEST_CASE("scene file: two_sided_emission true marks the mesh's emitters two-sided; absent, nothing changes" * doctest::test_suite("cpu")) {
  using namespace montecl;
  montecl_test::TempDir dir;
  const std::string quad = std::string(MONTECL_SOURCE_DIR) + "/scenes/test/good/quad.obj";
  const std::string cam = R"("camera": {"position": [0, 0, 2], "target": [0, 0, 0], "fov_y": 45, "width": 8, "height": 8})";
  dir.write("two.json", "{" + cam + R"(, "meshes": [{"file": ")" + quad + R"(", "emission": [1, 2, 3], "two_sided_emission": true}]})");
  dir.write("one.json", "{" + cam + R"(, "meshes": [{"file": ")" + quad + R"(", "emission": [1, 2, 3]}]})");
  std::vector<std::string> warnings;
  Scene two = loadScene(dir.file("two.json"), warnings);
  Scene one = loadScene(dir.file("one.json"), warnings);
  CHECK(warnings.empty());
  for (const SceneTriangle& t : two.triangles) {
    CHECK(two.materials[t.material].twoSidedEmission);
    CHECK(two.materials[t.material].emission == glm::vec3(1, 2, 3));
  }
  for (const SceneTriangle& t : one.triangles) CHECK_FALSE(one.materials[t.material].twoSidedEmission);
}

}  // namespace test_file_scene
