// test_cli_hostile.cpp: hand-made hostile inputs through the real command line, each once a crash,
// a hang, a wrong image or memory spent before a refusal: geometry too thin for the spatial-split
// binning, output names that are inputs in another case of their letters, light, material and
// texture-transform values the kernels cannot represent, instances out of float range, hand-edited
// merge sample counts, glTF values of the wrong type, instancing past the memory check, a shared
// accessor decoded per primitive, false "black image" warnings at tiny scales. Each ends in an
// image or in one line naming the file and key, exit 2, no output.
#include <doctest/doctest.h>

#include <sys/stat.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_checks.h"
#include "cli_runner.h"
#include "image/exr_layers.h"
#include "image/image_io.h"
#include "mesh_files.h"
#include "sanitizers.h"
#include "skip.h"

namespace test_file_cli_hostile {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;  // runMontecl, TempDir, checkRefused and the fixture's mesh files
namespace fs = std::filesystem;

namespace {

std::vector<std::string> renderArgs(const std::string& scene, const std::string& out) {
  return {"render", scene, "-o", out, "-q", "--device", "host", "--width", "16", "--height", "16", "--spp", "2"};
}

// The test fixture's glTF (a tent) with `ext` added to its top level and, when light is set, a
// second node holding KHR_lights_punctual light 0 above it.
std::string gltfWith(const std::string& ext, bool light) {
  std::string g = montecl_test::gltfText(montecl_test::tentMesh(), 0.5f, "");
  if (light) {
    const std::string nodes = R"("scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"translation":[0,0,0]}])";
    REQUIRE(g.find(nodes) != std::string::npos);
    g.replace(g.find(nodes), nodes.size(),
              R"("scenes":[{"nodes":[0,1]}],"nodes":[{"mesh":0,"translation":[0,0,0]},)"
              R"({"translation":[1,3,1],"extensions":{"KHR_lights_punctual":{"light":0}}}])");
  }
  g.insert(g.rfind('}'), "," + ext);
  return g;
}

std::string punctual(const std::string& lightJson) {
  return R"("extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":{"lights":[)" + lightJson + "]}}";
}

// A scene file: one quad under `lights`, its material `material`.
std::string sceneWith(const TempDir& dir, const std::string& material, const std::string& lights) {
  dir.write("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
  dir.write("scene.json", R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 45, "width": 16, "height": 16},
    "meshes": [{"file": "quad.obj", "material": )" + material + R"(}], "render": {"integrator": "path", "spp": 2},
    "lights": )" + lights + "}");
  return dir.file("scene.json");
}

}  // namespace

// Four overlapping triangles 2e-38 thick along z: the spatial-split binning's inverse slab width
// overflowed to inf, 0 * inf gave a NaN slab index, and the builder read far outside its planes.
TEST_CASE("hostile: a 9-line OBJ 2e-38 thick renders (the spatial-split builder skips a too-thin axis)" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("thin.obj", "v 0 0 0\nv 1 0 2e-38\nv 0 1 0\nv 1 1 2e-38\nv 0.5 0.5 0\nf 1 2 4\nf 1 4 3\nf 2 3 5\nf 1 2 3\n");
  const std::string out = dir.file("thin.png");
  CliResult r = runMontecl(renderArgs(dir.file("thin.obj"), out));
  INFO("exit " << r.exitCode << ": " << r.err);
  CHECK(r.exitCode == 0);
  CHECK(fs::exists(out));
}

// The glTF names Wood.PNG, the disk holds Wood.png, which the texture loader opens (any case of the
// name). -o Wood.PNG would replace the texture on a case-insensitive file system, and on Linux the
// model would read the render as Wood.PNG from then on: refused, as for the exact name.
TEST_CASE("hostile: -o naming a texture in another case of its letters is refused before any work" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  std::string gltf = montecl_test::gltfText(montecl_test::tentMesh(), 0.5f, "");
  const std::string pbr = R"("pbrMetallicRoughness":{)";
  gltf.replace(gltf.find(pbr), pbr.size(), pbr + R"("baseColorTexture":{"index":0},)");
  gltf.insert(gltf.rfind('}'), R"(,"textures":[{"source":0}],"images":[{"uri":"Wood.PNG"}])");
  dir.write("model.gltf", gltf);
  montecl::writeRgbImage(dir.file("Wood.png"), 2, 2, std::vector<float>(12, 0.5f));
  const std::string texture = montecl_test::readAll(dir.file("Wood.png"));
  // The model renders with its texture found in another case.
  CliResult ok = runMontecl(renderArgs(dir.file("model.gltf"), dir.file("render.png")));
  REQUIRE_MESSAGE(ok.exitCode == 0, ok.err);
  for (const char* name : {"Wood.PNG", "wood.png", "Wood.png"}) {
    CliResult r = runMontecl(renderArgs(dir.file("model.gltf"), dir.file(name)));
    INFO(name);
    INFO("exit " << r.exitCode << ", stderr: " << r.err);
    CHECK(r.exitCode == 2);
    // The loader's warning that it used Wood.png for Wood.PNG, then the one error line.
    const std::size_t error = r.err.find("montecl: error: ");
    REQUIRE(error != std::string::npos);
    CHECK(oneLine(r.err.substr(error)));
    CHECK(r.err.find("the output is an input of the render", error) != std::string::npos);
    CHECK(montecl_test::readAll(dir.file("Wood.png")) == texture);
  }
  CHECK_FALSE(fs::exists(dir.file("Wood.PNG")));
  CHECK_FALSE(fs::exists(dir.file("wood.png")));
}

// Values the kernels cannot represent, each once an all-black image with exit 0, or a render that
// finished and then failed with exit 1 ("check emission and camera") with nothing written.
TEST_CASE("hostile: light, sun, conductor and texture-transform values past float range are one line at load" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string out = dir.file("out.exr");
  struct Case {
    const char* name;
    std::string file, text;
    std::vector<std::string> words;
  };
  const std::string quadLight = R"([{"type": "point", "position": [0, 0, 2], "intensity": [1, 1, 1]}])";
  const std::vector<Case> cases = {
      {"glTF colour x intensity overflows float", "a.gltf",
       gltfWith(punctual(R"({"type":"point","color":[1e30,1e30,1e30],"intensity":1e30})"), true),
       {"a.gltf", "KHR_lights_punctual.lights[0].intensity"}},
      {"glTF intensity 1e25", "b.gltf", gltfWith(punctual(R"({"type":"point","intensity":1e25})"), true),
       {"b.gltf", "KHR_lights_punctual.lights[0].intensity", "1e+25"}},
      {"glTF texture transform 1e300", "c.gltf", "", {"c.gltf", "KHR_texture_transform.scale"}},
  };
  for (const Case& c : cases) {
    std::string text = c.text;
    if (text.empty()) {  // the tent with a texture whose transform scales by 1e300
      montecl::writeRgbImage(dir.file("t.png"), 2, 2, std::vector<float>(12, 0.5f));
      text = gltfWith(R"("textures":[{"source":0}],"images":[{"uri":"t.png"}])", false);
      const std::string pbr = R"("pbrMetallicRoughness":{)";
      text.replace(text.find(pbr), pbr.size(),
                   pbr + R"("baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":{"scale":[1e300,1]}}},)");
    }
    dir.write(c.file, text);
    INFO(c.name);
    checkRefused(runMontecl(renderArgs(dir.file(c.file), out)), out, c.words);
  }
  // The scene file's sun and conductor.
  const std::string sun = sceneWith(
      dir, R"({"albedo": [0.5, 0.5, 0.5]})",
      R"([{"type": "sun", "direction": [0, 0, -1], "irradiance": [1, 1, 1], "angle": 1e-20}])");
  checkRefused(runMontecl(renderArgs(sun, out)), out, {"scene.json", "lights[0].angle"});
  const std::string metal = sceneWith(dir, R"({"type": "conductor", "eta": [3.4e38, 1, 1]})", quadLight);
  checkRefused(runMontecl(renderArgs(metal, out)), out, {"scene.json", "eta", "3.4e+38"});
  const std::string bright = sceneWith(
      dir, R"({"albedo": [0.5, 0.5, 0.5]})", R"([{"type": "point", "position": [0, 0, 2], "intensity": [1e25, 1, 1]}])");
  checkRefused(runMontecl(renderArgs(bright, out)), out, {"scene.json", "lights[0].intensity"});
  // The limits leave ordinary values alone: a 0.53-degree sun and gold render.
  const std::string fine = sceneWith(
      dir, R"({"type": "conductor", "metal": "Au"})",
      R"([{"type": "sun", "direction": [0, 0, -1], "irradiance": [3, 3, 3], "angle": 0.53}])");
  CliResult r = runMontecl(renderArgs(fine, out));
  CHECK_MESSAGE(r.exitCode == 0, r.err);
}

// Instances placed past the BVH's float range, or whose inverse leaves float range, exited 1 with
// buildBvh's or buildTwoLevelBvh's internal message naming no file or key.
TEST_CASE("hostile: an instance placed past float range or with an overflowing inverse names the file and key" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string out = dir.file("out.png");
  for (const char* placement : {R"({"translate": [2e19, 0, 0]})", R"({"scale": [1e-30, 1e-30, 1e-30]})"}) {
    dir.write("scene.json", std::string(R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 45, "width": 16, "height": 16},
      "meshes": [{"file": "tri.obj", "transform": {"scale": 1e-12}, "instances": [{"translate": [0, 0, 0]}, )") + placement +
                                R"(]}], "render": {"integrator": "ao", "spp": 1}})");
    INFO(placement);
    checkRefused(runMontecl(renderArgs(dir.file("scene.json"), out)), out, {"scene.json", "meshes[0].instances[1]"});
  }
}

// A tent instanced with a scale of 1e-20 along z rendered 16 of 256 pixels differently from the
// same tent flattened with that scale (the ray entering the instance is the world direction
// times 1e20 along z, and the traversal squares its length in float); 1e-19 still agreed. Past
// 1e18 the inverse scale is refused, naming the instance.
TEST_CASE("hostile: an instance scaled by 1e-20 along one axis is refused, naming the instance" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("tent.obj", "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 1 -1\nv 0 1 1\nf 1 2 3 4\nf 1 5 2\nf 4 3 6\n");
  const std::string out = dir.file("out.png");
  for (const char* scale : {"1e-20", "1e-5"}) {
    dir.write("scene.json", std::string(R"({"camera": {"position": [0.5, 3, 2], "target": [0, 0, 0], "fov_y": 50, "width": 16, "height": 16},
      "meshes": [{"file": "tent.obj", "instances": [{"translate": [9, 0, 0]}, {"scale": [1, 1, )") + scale +
                                R"(]}]}], "render": {"integrator": "ao", "spp": 4}})");
    CliResult r = runMontecl(renderArgs(dir.file("scene.json"), out));
    INFO(scale << ": exit " << r.exitCode << ": " << r.err);
    if (std::string(scale) == "1e-5") {
      CHECK(r.exitCode == 0);  // an ordinary flattening scale stays an instance
    } else {
      checkRefused(r, out, {"scene.json", "meshes[0].instances[1]", "inverse"});
    }
  }
}

// A hand-edited sample count of -1, 2.5 or 1e30 weighted its pixel by nonsense (a negative one
// was taken as 0), with exit 0.
TEST_CASE("hostile: merge refuses negative, fractional and huge sample counts" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  auto image = [](float count) {
    montecl::LayeredImage im;
    im.width = 2;
    im.height = 2;
    for (const char* c : {"R", "G", "B"}) im.set(c, std::vector<float>(4, 0.5f));
    im.set("samples", {4.0f, 4.0f, 4.0f, count});
    return im;
  };
  montecl::writeLayeredExr(dir.file("a.exr"), image(4.0f));
  const std::string out = dir.file("m.exr");
  for (float bad : {-1.0f, 2.5f, 1e30f}) {
    montecl::writeLayeredExr(dir.file("bad.exr"), image(bad));
    INFO(bad);
    checkRefused(runMontecl({"merge", dir.file("a.exr"), dir.file("bad.exr"), "-o", out, "--force", "-q"}), out,
                 {"bad.exr", "pixel (1, 1) channel 'samples'", "whole number"});
  }
  montecl::writeLayeredExr(dir.file("b.exr"), image(7.0f));
  CliResult ok = runMontecl({"merge", dir.file("a.exr"), dir.file("b.exr"), "-o", out, "--force", "-q"});
  CHECK_MESSAGE(ok.exitCode == 0, ok.err);
}

// tinygltf leaves a value of the wrong JSON type at its default ("intensity": "x" rendered at 1),
// and a node's camera index past the cameras was ignored (the model framed itself, unasked).
TEST_CASE("hostile: glTF light values of the wrong type and a camera index out of range name the key" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string out = dir.file("out.png");
  const std::vector<std::pair<std::string, std::string>> lights = {
      {R"({"type":"point","intensity":"x"})", "KHR_lights_punctual.lights[0].intensity"},
      {R"({"type":"point","color":[1,"1",1]})", "KHR_lights_punctual.lights[0].color"},
      {R"({"type":"spot","spot":{"outerConeAngle":"wide"}})", "KHR_lights_punctual.lights[0].spot.outerConeAngle"},
      {R"({"type":"point","range":[1]})", "KHR_lights_punctual.lights[0].range"},
  };
  for (const auto& entry : lights) {  // not a structured binding: INFO captures it in a lambda (clang 14)
    const std::string light = entry.first;
    dir.write("a.gltf", gltfWith(punctual(light), true));
    INFO(light);
    checkRefused(runMontecl(renderArgs(dir.file("a.gltf"), out)), out, {"a.gltf", entry.second});
  }
  std::string g = montecl_test::gltfText(montecl_test::tentMesh(), 0.5f, "");
  const std::string node = R"("nodes":[{"mesh":0,)";
  g.replace(g.find(node), node.size(), R"("nodes":[{"mesh":0,"camera":3,)");
  g.insert(g.rfind('}'), R"(,"cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":0.1}}])");
  dir.write("b.gltf", g);
  checkRefused(runMontecl(renderArgs(dir.file("b.gltf"), out)), out, {"b.gltf", "nodes[0].camera", "out of range"});
}

// A mesh placed by 10000 nodes loads as one mesh and 10000 instances; an emission override in the
// scene file makes it copies (the emitter table is world space): 40000 triangles that were made
// with no memory check on a machine declared to have 8 MB. Now refused before one is made.
TEST_CASE("hostile: an emission override flattening an instanced glTF counts the copies against the memory check" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  nlohmann::json j = nlohmann::json::parse(montecl_test::gltfText(montecl_test::tentMesh(), 0.5f, ""));
  j["nodes"] = nlohmann::json::array();
  j["scenes"][0]["nodes"] = nlohmann::json::array();
  for (int i = 0; i < 10000; ++i) {
    j["nodes"].push_back({{"mesh", 0}, {"translation", {0, 0, -0.001 * i}}});
    j["scenes"][0]["nodes"].push_back(i);
  }
  dir.write("many.gltf", j.dump());
  const std::string out = dir.file("out.png");
  const std::vector<std::string> limit = {"MONTECL_MEMORY_LIMIT=8000000"};
  dir.write("plain.json", R"({"camera": "auto", "meshes": [{"file": "many.gltf"}], "render": {"integrator": "direct", "spp": 1}})");
  CliResult plain = runMontecl(renderArgs(dir.file("plain.json"), out), limit);
  REQUIRE_MESSAGE(plain.exitCode == 0, plain.err);  // as instances it fits
  fs::remove(out);
  dir.write("lit.json", R"({"camera": "auto", "meshes": [{"file": "many.gltf", "emission": [1, 1, 1]}], "render": {"integrator": "direct", "spp": 1}})");
  checkRefused(runMontecl(renderArgs(dir.file("lit.json"), out), limit), out,
               {"lit.json", "meshes[0]", "flattening its instances", "this machine has"});
}

// EXT_mesh_gpu_instancing declaring a million placements on a machine declared to have 200 MB: the
// loader made all their matrices (128 MB) before the memory check refused the instances (480 MB).
// Counted first, the refusal comes before they exist. The peak is measured with the child's
// rusage (python3), so the case skips without python3, and under AddressSanitizer, whose shadow
// memory is in the peak.
TEST_CASE("hostile: glTF instancing placements are counted against the memory check before any is made" *
          doctest::test_suite("cli")) {
  MCL_SKIP_UNLESS(!MCL_TEST_UNDER_ASAN, "under AddressSanitizer the peak holds its shadow memory");
  MCL_SKIP_UNLESS(montecl_test::runProgram({"python3", "-c", "pass"}).exitCode == 0, "no python3 to measure the peak");
  TempDir dir;
  const std::size_t count = 1000000;
  dir.write("t.bin", std::string(count * 12, '\0'));
  nlohmann::json j = nlohmann::json::parse(montecl_test::gltfText(montecl_test::tentMesh(), 0.5f, ""));
  j["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  j["buffers"].push_back({{"uri", "t.bin"}, {"byteLength", count * 12}});
  j["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 0}, {"byteLength", count * 12}});
  j["accessors"].push_back({{"bufferView", j["bufferViews"].size() - 1}, {"componentType", 5126}, {"count", count}, {"type", "VEC3"}});
  j["nodes"][0]["extensions"] = {{"EXT_mesh_gpu_instancing", {{"attributes", {{"TRANSLATION", j["accessors"].size() - 1}}}}}};
  dir.write("placed.gltf", j.dump());
  const std::string out = dir.file("out.png");
  const char* script =
      "import resource, subprocess, sys\n"
      "r = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)\n"
      "sys.stderr.write(r.stderr.decode())\n"
      "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n"
      "sys.exit(r.returncode)\n";
  std::vector<std::string> args = {"python3", "-c", script, MONTECL_EXE};
  for (const std::string& a : renderArgs(dir.file("placed.gltf"), out)) args.push_back(a);
  CliResult r = montecl_test::runProgram(args, {"MONTECL_MEMORY_LIMIT=200000000"});
  INFO(r.err);
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("1000000 instances") != std::string::npos);
  const long peakKiB = std::atol(r.out.c_str());
  INFO("peak " << peakKiB << " KiB");
  CHECK(peakKiB > 0);
  CHECK(peakKiB < 100 * 1024);  // the buffer and its floats (24 MB) and the process, not 128 MB of matrices
}

// 20,000 primitives over one shared POSITION accessor of 150,000 vertices: each primitive decoded
// the whole accessor again (9e9 floats, about 15 s on two cores; a real file cost 41 s of CPU).
// Decoded once, the render takes under a second (0.3 s release, 3.6 s under ASan + UBSan, 6.4 s
// under ASan on a machine at load 10: 2026-12-07); 10 s leaves room for a loaded sanitized run.
TEST_CASE("hostile: primitives sharing one accessor decode it once" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const int vertices = 150000, primitives = 20000;
  std::string buffer(std::size_t(vertices) * 12 + 12, '\0');
  for (int v = 0; v < vertices; ++v) {
    const float p[3] = {float(v % 3 == 1), float(v % 3 == 2), 0.0f};
    std::memcpy(&buffer[std::size_t(v) * 12], p, 12);
  }
  const std::uint32_t tri[3] = {0, 1, 2};
  std::memcpy(&buffer[std::size_t(vertices) * 12], tri, 12);
  dir.write("shared.bin", buffer);
  std::string prims;
  for (int k = 0; k < primitives; ++k) prims += std::string(k ? "," : "") + R"({"attributes":{"POSITION":0},"indices":1})";
  dir.write("shared.gltf",
            R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[)" +
                prims + R"(]}],"buffers":[{"uri":"shared.bin","byteLength":)" + std::to_string(buffer.size()) +
                R"(}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" + std::to_string(vertices * 12) +
                R"(},{"buffer":0,"byteOffset":)" + std::to_string(vertices * 12) +
                R"(,"byteLength":12}],"accessors":[{"bufferView":0,"componentType":5126,"count":)" +
                std::to_string(vertices) + R"(,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
                R"({"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}]})");
  const auto start = std::chrono::steady_clock::now();
  CliResult r = runMontecl({"render", dir.file("shared.gltf"), "-o", dir.file("out.png"), "-q", "--device", "host",
                            "--width", "8", "--height", "8", "--spp", "1", "--integrator", "ao"});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  INFO(r.err);
  CHECK(r.exitCode == 0);
  CHECK(seconds < 10.0);
}

// A lit floor and a light facing it, scaled by 2^-30 and 2^-40, render as lit as at scale 1, but
// warned "no emitter's front face faces any surface" and "nothing emits: the image is black" (the
// tests ran in float with an absolute tolerance).
TEST_CASE("hostile: a lit scene scaled by 2^-30 or 2^-40 is not warned black" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("floor.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
  dir.write("light.obj", "v -0.2 -0.2 1\nv -0.2 0.2 1\nv 0.2 0.2 1\nv 0.2 -0.2 1\nf 1 2 3 4\n");
  for (const char* scale : {"1", "9.313225746154785e-10", "9.094947017729282e-13"}) {
    dir.write("scene.json", std::string(R"({"camera": "auto", "meshes": [{"file": "floor.obj", "transform": {"scale": )") +
                                scale + R"(}}, {"file": "light.obj", "emission": [10, 10, 10], "transform": {"scale": )" +
                                scale + R"(}}], "render": {"integrator": "direct", "spp": 2}})");
    CliResult r = runMontecl(renderArgs(dir.file("scene.json"), dir.file("out.png")));
    INFO(scale << ": " << r.err);
    CHECK(r.exitCode == 0);
    CHECK(r.err.find("warning") == std::string::npos);
    fs::remove(dir.file("out.png"));
  }
}

// An 8 x 4096 EXR whose header is patched to declare 4096 x 4096: its chunks and offset table are
// all there, but its few kilobytes cannot hold 200 MB of pixels (no compression reaches that),
// yet the environment map and merge readers allocated the whole declared image before the decoder
// found the chunks short (a 9.8 KB file cost 7.2 GB and 17-47 s). Now refused from the header.
TEST_CASE("hostile: an EXR declaring more pixels than its file can hold is refused before decoding" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  montecl::writeRgbImage(dir.file("small.exr"), 8, 4096, std::vector<float>(8 * 4096 * 3, 0.5f));
  std::string bytes = montecl_test::readAll(dir.file("small.exr"));
  const std::string key = std::string("dataWindow\0box2i\0", 17);
  const std::size_t at = bytes.find(key);
  REQUIRE(at != std::string::npos);
  const std::int32_t window[4] = {0, 0, 4095, 4095};
  std::memcpy(&bytes[at + key.size() + 4], window, sizeof window);  // after the attribute's size
  dir.write("huge.exr", bytes);
  const std::string out = dir.file("out.exr");
  checkRefused(runMontecl({"render", montecl_test::demoScene(), "-o", out, "-q", "--device", "host", "--width", "8",
                           "--height", "8", "--spp", "1", "--env", dir.file("huge.exr")}),
               out, {"huge.exr", "declares", "bytes of pixels in a file of"});
  checkRefused(runMontecl({"merge", dir.file("small.exr"), dir.file("huge.exr"), "-o", out, "--force", "-q"}), out,
               {"huge.exr", "declares", "bytes of pixels in a file of"});
}

// A command-line mistake printed CLI11's message and "Run with --help for more information." on a
// second line, without montecl's prefix: now one line, exit 2.
TEST_CASE("hostile: command-line mistakes are one error line" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string out = dir.file("out.png");
  const std::vector<std::vector<std::string>> mistakes = {
      {"render", demoScene(), "-o", out, "--spp", "x"},
      {"render", demoScene(), "-o", out, "--bogus"},
      {"render"},
      {"render", demoScene(), "-o", out, "-o", dir.file("b.png")},
  };
  for (const std::vector<std::string>& args : mistakes) {
    CliResult r = runMontecl(args);
    INFO(args.back() << ": " << r.err);
    checkRefused(r, out, {"montecl: error: ", "--help"});
  }
  CliResult help = runMontecl({"render", "--help"});
  CHECK(help.exitCode == 0);
  CHECK(help.out.find("--spp") != std::string::npos);
}

}  // namespace test_file_cli_hostile
