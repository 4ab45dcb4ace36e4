// test_missing_textures.cpp: --missing-textures / render.missing_textures through the real command
// line: with warn every texture the scene cannot open (MTL, glTF image, a scene file's texture
// key) is named in one warning and the materials render as their factors, exactly as the scene
// without those texture statements does; with error (the default, and --missing-textures error
// over a scene file's warn) all are named in one line, exit 2, nothing written.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "mesh_files.h"

namespace test_file_missing_textures {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)
using nlohmann::json;

namespace {

const char* kQuads =
    "mtllib quads.mtl\nv -1 -1 0\nv 0 -1 0\nv 0 1 0\nv -1 1 0\nv 1 -1 0\nv 1 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3 4/4\nusemtl b\nf 2/1 5/2 6/3 3/4\n";

// The tent glTF with a base colour texture whose file is named `uri`.
std::string texturedTent(const std::string& uri) {
  json g = json::parse(montecl_test::gltfText(montecl_test::tentMesh(), 0.5f, ""));
  g["images"] = {{{"uri", uri}}};
  g["textures"] = {{{"source", 0}}};
  g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  g["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.25, 0.5, 0.75, 1};
  return g.dump();
}

json sceneWith(const json& render) {
  return {{"camera", {{"position", {0, 0.5, 5}}, {"target", {0, 0, -1}}, {"fov_y", 60}}},
          {"render", render},
          {"meshes", {{{"file", "quads.obj"}},
                      {{"file", "tent.gltf"}, {"transform", {{"translate", {0, 0, -2}}}}},
                      {{"file", "quads.obj"}, {"transform", {{"translate", {0, -2.5, -1}}}},
                       {"material", {{"albedo", {0.2, 0.4, 0.6}}, {"albedo_texture", "nowhere/gone4.png"}}}}}}};
}

CliResult render(const std::string& scene, const std::string& out, const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{"--integrator", "ao", "--aov", "albedo"};
  args.insert(args.end(), extra.begin(), extra.end());
  return renderOnHost(scene, out, args, {}, 24, 16);
}

std::size_t lines(const std::string& s) { return std::size_t(std::count(s.begin(), s.end(), '\n')); }

}  // namespace

TEST_CASE("missing textures: warn names all in one warning and renders the factors; error stops with one line" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("quads.obj", kQuads);
  dir.write("quads.mtl", "newmtl a\nKd 0.25 0.5 0.75\nmap_Kd gone1.png\nnewmtl b\nmap_Kd maps/gone2.png\n");
  dir.write("tent.gltf", texturedTent("gone3.png"));
  dir.write("scene.json", sceneWith(json::object()).dump());
  // Warn from the command line: exit 0, one warning naming all four, the image written.
  const CliResult warn = render(dir.file("scene.json"), dir.file("warn.exr"), {"--missing-textures", "warn"});
  INFO(warn.err);
  REQUIRE(warn.exitCode == 0);
  CHECK(lines(warn.err) == 1);
  for (const std::string& name : {std::string("'gone1.png'"), std::string("'maps/gone2.png'"), dir.file("gone3.png"),
                                  dir.file("nowhere/gone4.png")})
    CHECK(warn.err.find(name) != std::string::npos);
  CHECK(warn.err.find(dir.file("quads.mtl") + " line 3 map_Kd 'gone1.png'") != std::string::npos);
  CHECK(warn.err.find("(4 textures missing)") != std::string::npos);  // quads.obj is read twice, named once
  // The same scene without the texture statements: the same albedo and image, exactly.
  TempDir plain;
  plain.write("quads.obj", kQuads);
  plain.write("quads.mtl", "newmtl a\nKd 0.25 0.5 0.75\nnewmtl b\n");
  json tent = json::parse(texturedTent("x.png"));
  tent.erase("images");
  tent.erase("textures");
  tent["materials"][0]["pbrMetallicRoughness"].erase("baseColorTexture");
  plain.write("tent.gltf", tent.dump());
  json scene = sceneWith(json::object());
  scene["meshes"][2]["material"].erase("albedo_texture");
  plain.write("scene.json", scene.dump());
  const CliResult expected = render(plain.file("scene.json"), plain.file("plain.exr"));
  REQUIRE_MESSAGE(expected.exitCode == 0, expected.err);
  const montecl::LayeredImage a = montecl::readLayeredImage(dir.file("warn.exr"));
  const montecl::LayeredImage b = montecl::readLayeredImage(plain.file("plain.exr"));
  for (const char* layer : {"R", "G", "B", "albedo.R", "albedo.G", "albedo.B"}) {
    CAPTURE(layer);
    REQUIRE(a.find(layer));
    REQUIRE(b.find(layer));
    CHECK(*a.find(layer) == *b.find(layer));
  }
  // The albedo shows the factors (not black, not white): some pixel has material a's 0.25, 0.5, 0.75.
  bool sawA = false;
  for (std::size_t i = 0; i < a.pixelCount(); ++i)
    sawA = sawA || ((*a.find("albedo.R"))[i] == 0.25f && (*a.find("albedo.B"))[i] == 0.75f);
  CHECK(sawA);

  // The scene file's render.missing_textures warn does the same; --missing-textures error overrides it.
  dir.write("scene.json", sceneWith({{"missing_textures", "warn"}}).dump());
  const CliResult fileWarn = render(dir.file("scene.json"), dir.file("filewarn.exr"));
  CHECK_MESSAGE(fileWarn.exitCode == 0, fileWarn.err);
  CHECK(lines(fileWarn.err) == 1);
  for (const std::vector<std::string>& extra : {std::vector<std::string>{"--missing-textures", "error"}, std::vector<std::string>{}}) {
    if (extra.empty()) dir.write("scene.json", sceneWith(json::object()).dump());  // the default: error
    const CliResult error = render(dir.file("scene.json"), dir.file("error.exr"), extra);
    INFO(error.err);
    CHECK(error.exitCode == 2);
    CHECK(lines(error.err) == 1);
    CHECK(error.err.find(dir.file("quads.mtl") + " line 3 map_Kd 'gone1.png'") != std::string::npos);
    CHECK(error.err.find(dir.file("quads.mtl") + " line 5 map_Kd 'maps/gone2.png'") != std::string::npos);
    CHECK(error.err.find(dir.file("gone3.png")) != std::string::npos);
    CHECK(error.err.find(dir.file("nowhere/gone4.png")) != std::string::npos);
    CHECK(error.err.find("(4 textures missing)") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir.file("error.exr")));
  }
  // A bad value: one line naming the option.
  const CliResult bad = render(dir.file("scene.json"), dir.file("bad.exr"), {"--missing-textures", "ignore"});
  CHECK(bad.exitCode == 2);
  CHECK(bad.err.find("--missing-textures") != std::string::npos);
}

}  // namespace test_file_missing_textures
