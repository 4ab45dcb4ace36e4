// test_cli_guards.cpp: `montecl render` refuses, with one line and exit 2 and no file written,
// what would lose data or crash: an output that is a texture named in a scene file's mesh material
// override, or a glTF buffer whose URI is percent-encoded (the file as opened is the input); a
// glTF (.gltf, .glb, or through a scene file) or scene file nested thousands of arrays deep (a
// stack overflow in the JSON conversion); a sample range past 2^32 (it would wrap to sample 0
// while the EXR's provenance says otherwise); a --texture-budget whose byte count overflows 64 bits;
// a GLB whose BIN chunk runs past the file or whose BIN-chunk buffer has byteLength 0; a mesh
// transform that leaves no triangle; a --split-budget of NaN. Under `ulimit -f`, a write that
// passes the limit fails with one line and exit 1, no partial file (not death by SIGXFSZ).
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "cli_runner.h"
#include "image/image_io.h"
#include "mesh_files.h"

namespace test_file_cli_guards {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)
namespace fs = std::filesystem;

namespace {

// A quad (with uvs) and a scene file whose mesh entry has the given "material" override JSON.
std::string writeOverrideScene(const TempDir& dir, const std::string& material) {
  dir.write("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n");
  dir.write("scene.json", R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 45, "width": 8, "height": 8},
    "meshes": [{"file": "quad.obj", "material": )" + material + "}]}");
  return dir.file("scene.json");
}

// The JSON text with `"extras": [[...]]` nested `depth` deep inserted after its first '{'.
std::string withDeepExtras(const std::string& json, int depth) {
  return "{\"extras\": " + std::string(std::size_t(depth), '[') + std::string(std::size_t(depth), ']') + ", " +
         json.substr(json.find('{') + 1);
}

// A GLB whose JSON chunk is replaced by `json` (padded with spaces; the BIN chunk kept).
std::string glbWithJson(const std::string& glb, std::string json) {
  std::uint32_t oldLength = 0;
  std::memcpy(&oldLength, glb.data() + 12, 4);
  while (json.size() % 4) json += ' ';
  std::string out = glb.substr(0, 12);
  const std::uint32_t length = std::uint32_t(json.size());
  out.append(reinterpret_cast<const char*>(&length), 4);
  out.append(glb, 16, 4);  // chunk type JSON
  out += json;
  out += glb.substr(20 + oldLength);
  const std::uint32_t total = std::uint32_t(out.size());
  std::memcpy(out.data() + 8, &total, 4);
  return out;
}

}  // namespace

TEST_CASE("cli: an output that is a mesh material override's texture is refused (exit 2), the texture untouched" * doctest::test_suite("cli sanitize")) {
  for (const char* key : {"albedo_texture", "alpha_texture"}) {
    TempDir dir;
    montecl::writeRgbImage(dir.file("wood.png"), 2, 2, std::vector<float>(12, 0.25f));
    const std::string before = readAll(dir.file("wood.png"));
    const std::string scene = writeOverrideScene(dir, std::string("{\"") + key + "\": \"wood.png\"}");
    CliResult r = renderOnHost(scene, dir.file("wood.png"));
    INFO(key << ": " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.find("input") != std::string::npos);
    CHECK(readAll(dir.file("wood.png")) == before);
  }
}

TEST_CASE("cli: an output that is a glTF buffer named by a percent-encoded URI is refused (exit 2), the buffer untouched" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const montecl_test::MeshData mesh = montecl_test::tentMesh();
  // The buffer's file is "geo data.pfm" (an image extension, so -o may name it); the URI encodes the space.
  dir.write("geo data.pfm", montecl_test::gltfBuffer(mesh));
  dir.write("model.gltf", montecl_test::gltfText(mesh, 0.5f, "geo%20data.pfm"));
  const std::string before = readAll(dir.file("geo data.pfm"));
  CliResult ok = renderOnHost(dir.file("model.gltf"), dir.file("out.png"));
  REQUIRE_MESSAGE(ok.exitCode == 0, ok.err);  // the model loads: its buffer is that file
  CliResult r = renderOnHost(dir.file("model.gltf"), dir.file("geo data.pfm"));
  INFO(r.err);
  CHECK(r.exitCode == 2);
  CHECK(oneLine(r.err));
  CHECK(r.err.find("input") != std::string::npos);
  CHECK(readAll(dir.file("geo data.pfm")) == before);
}

TEST_CASE("cli: a glTF or scene file nested 15000 arrays deep is refused with one line, not a crash" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const montecl_test::MeshData mesh = montecl_test::tentMesh();
  dir.write("deep.gltf", withDeepExtras(montecl_test::gltfText(mesh, 0.5f, ""), 15000));
  dir.write("deep.glb", glbWithJson(montecl_test::glbBytes(mesh, 0.5f), withDeepExtras(
      [&] {  // the GLB's own JSON chunk
        const std::string glb = montecl_test::glbBytes(mesh, 0.5f);
        std::uint32_t length = 0;
        std::memcpy(&length, glb.data() + 12, 4);
        return glb.substr(20, length);
      }(), 15000)));
  const std::string camera = R"("camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 45, "width": 8, "height": 8})";
  dir.write("scene.json", "{" + camera + R"(, "meshes": [{"file": "deep.gltf"}]})");
  dir.write("deepscene.json", withDeepExtras("{" + camera + R"(, "meshes": [{"file": "ok.gltf"}]})", 15000));
  dir.write("ok.gltf", montecl_test::gltfText(mesh, 0.5f, ""));
  // Just under the limit loads (the extras are ignored).
  dir.write("shallow.gltf", withDeepExtras(montecl_test::gltfText(mesh, 0.5f, ""), 500));
  CliResult ok = renderOnHost(dir.file("shallow.gltf"), dir.file("out.png"));
  CHECK_MESSAGE(ok.exitCode == 0, ok.err);
  struct Case {
    std::string input, named;
  };
  for (const Case& c : {Case{"deep.gltf", "deep.gltf"}, Case{"deep.glb", "deep.glb"}, Case{"scene.json", "deep.gltf"},
                        Case{"deepscene.json", "deepscene.json"}}) {
    fs::remove(dir.file("out.png"));
    CliResult r = renderOnHost(dir.file(c.input), dir.file("out.png"));
    INFO(c.input << ": exit " << r.exitCode << ": " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.find(c.named + ": line 1: nesting deeper than 512") != std::string::npos);
    CHECK(!fs::exists(dir.file("out.png")));
  }
}

TEST_CASE("cli: a sample range past 2^32 is refused (exit 2), not wrapped to sample 0" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string scene = montecl_test::demoScene();
  const std::string out = dir.file("out.exr");
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--first-sample", "4294967295", "--spp", "2"},
        std::vector<std::string>{"--first-sample", "4294967200", "--target-error", "0.1", "--min-spp", "4", "--max-spp", "200"}}) {
    CliResult r = renderOnHost(scene, out, extra);
    INFO(extra[1] << ": " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.find("--first-sample") != std::string::npos);
    CHECK(!fs::exists(out));
  }
  // The last samples of the sequence still render.
  CliResult r = renderOnHost(scene, out, {"--first-sample", "4294967294", "--spp", "2"});
  CHECK_MESSAGE(r.exitCode == 0, r.err);
}

TEST_CASE("cli: a --texture-budget whose byte count overflows 64 bits is refused (exit 2)" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  montecl::writeRgbImage(dir.file("wood.png"), 4, 4, std::vector<float>(48, 0.25f));
  const std::string scene = writeOverrideScene(dir, R"({"albedo_texture": "wood.png"})");
  for (const std::string budget : {"17592186044416", "1e30"}) {  // 2^44 MiB: 2^64 bytes, which wrapped to 0
    CliResult r = renderOnHost(scene, dir.file("out.png"), {"--texture-budget", budget});
    INFO(budget << ": " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.find("--texture-budget") != std::string::npos);
    CHECK(!fs::exists(dir.file("out.png")));
  }
  CliResult r = renderOnHost(scene, dir.file("out.png"), {"--texture-budget", "8796093022208"});  // 2^43 MiB fits
  CHECK_MESSAGE(r.exitCode == 0, r.err);
  CHECK(r.err.find("budget") == std::string::npos);  // no level dropped
}

namespace {

// The tent GLB's JSON chunk, parsed.
nlohmann::json glbJson(const std::string& glb) {
  std::uint32_t length = 0;
  std::memcpy(&length, glb.data() + 12, 4);
  return nlohmann::json::parse(glb.substr(20, length));
}

}  // namespace

TEST_CASE("cli: a GLB whose BIN chunk claims more bytes than the file holds is refused (exit 2), not read past" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string glb = montecl_test::glbBytes(montecl_test::tentMesh(), 0.5f);
  nlohmann::json j = glbJson(glb);
  std::uint32_t jsonLength = 0, binLength = 0;
  std::memcpy(&jsonLength, glb.data() + 12, 4);
  std::memcpy(&binLength, glb.data() + 20 + jsonLength, 4);
  // The chunk and its buffer claim 8 bytes more: exactly the file's end counted from the chunk's
  // header, which tinygltf's own check (it forgets the header) lets through.
  j["buffers"][0]["byteLength"] = binLength + 8;
  std::string bad = glbWithJson(glb, j.dump());
  std::memcpy(&jsonLength, bad.data() + 12, 4);
  const std::uint32_t claimed = std::uint32_t(bad.size() - 20 - jsonLength);
  std::memcpy(bad.data() + 20 + jsonLength, &claimed, 4);
  dir.write("long.glb", bad);
  CliResult r = renderOnHost(dir.file("long.glb"), dir.file("out.png"));
  INFO("exit " << r.exitCode << ": " << r.err);
  CHECK(r.exitCode == 2);
  CHECK(oneLine(r.err));
  CHECK(r.err.find(dir.file("long.glb") + ": BIN chunk: claims " + std::to_string(claimed) + " bytes") != std::string::npos);
  CHECK(!fs::exists(dir.file("out.png")));
}

TEST_CASE("cli: a GLB buffer of byteLength 0 is refused with one line naming the file and the buffer (exit 2)" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string glb = montecl_test::glbBytes(montecl_test::tentMesh(), 0.5f);
  nlohmann::json j = glbJson(glb);
  j["buffers"][0]["byteLength"] = 0;
  dir.write("empty.glb", glbWithJson(glb, j.dump()));
  CliResult r = renderOnHost(dir.file("empty.glb"), dir.file("out.png"));
  INFO("exit " << r.exitCode << ": " << r.err);
  CHECK(r.exitCode == 2);
  CHECK(oneLine(r.err));
  CHECK(r.err.find(dir.file("empty.glb") + ": buffers[0]: byteLength 0") != std::string::npos);
  CHECK(r.err.find("range_check") == std::string::npos);
  CHECK(!fs::exists(dir.file("out.png")));
}

TEST_CASE("cli: a mesh transform that leaves no triangle is refused naming the scene file (exit 2)" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
  // Scaled by 1e-30 every triangle's area underflows to 0: all of them are dropped as degenerate.
  dir.write("scene.json", R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 45, "width": 8, "height": 8},
    "meshes": [{"file": "quad.obj", "transform": {"scale": 1e-30}}]})");
  CliResult r = renderOnHost(dir.file("scene.json"), dir.file("out.png"));
  INFO("exit " << r.exitCode << ": " << r.err);
  CHECK(r.exitCode == 2);
  CHECK(oneLine(r.err));
  CHECK(r.err.find(dir.file("scene.json") + ": meshes[0].transform: leaves the scene with no triangles") !=
        std::string::npos);
  CHECK(r.err.find("buildBvh") == std::string::npos);
  CHECK(!fs::exists(dir.file("out.png")));
}

TEST_CASE("cli: --split-budget nan is refused with the option's rule (exit 2)" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string scene = montecl_test::demoScene();
  for (const std::string value : {"nan", "-nan", "5", "-1"}) {
    CliResult r = renderOnHost(scene, dir.file("out.png"), {"--split-budget", value});
    INFO(value << ": exit " << r.exitCode << ": " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(r.err.find("--split-budget") != std::string::npos);
    CHECK(r.err.find("must be a number from 0 to 4, got '" + value + "'") != std::string::npos);
    CHECK(!fs::exists(dir.file("out.png")));
  }
  CliResult r = renderOnHost(scene, dir.file("out.png"), {"--split-budget", "4"});
  CHECK_MESSAGE(r.exitCode == 0, r.err);
}

TEST_CASE("cli: an EXR or PFM output past ulimit -f fails with one line (exit 1) and no partial file, not SIGXFSZ" *
          doctest::test_suite("cli sanitize")) {
  const std::string scene = montecl_test::demoScene();
  for (const char* name : {"out.exr", "out.pfm"}) {
    TempDir dir;
    // 100 blocks (at most 100 KiB) against a 512x512 float image (3 MiB as PFM, over 100 KiB as EXR).
    const std::string cmd = "ulimit -f 100; exec \"$0\" render \"$1\" -q --device host --spp 1 --width 512 "
                            "--height 512 -o \"$2\"";
    CliResult r = montecl_test::runProgram({"sh", "-c", cmd, MONTECL_EXE, scene, dir.file(name)});
    INFO(std::string(name) << ": exit " << r.exitCode << ": " << r.err);
    CHECK(r.exitCode == 1);
    CHECK(oneLine(r.err));
    CHECK(r.err.find(name) != std::string::npos);
    CHECK(r.err.find("File too large") != std::string::npos);  // EFBIG, the write's own reason
    CHECK(!fs::exists(dir.file(name)));
    CHECK(dir.entries().empty());  // no temporary left behind either
  }
}

}  // namespace test_file_cli_guards
