// test_texture_paths.cpp: texture names as exporters write them, through the command line: a name
// that differs from the file only in case (file or folder) is used with one warning and renders as
// the exact name does; every texture an OBJ's materials miss is named in one error line, exit 2.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "mesh_files.h"
#include "test_images.h"

namespace test_file_texture_paths {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)

namespace {

const char* kQuad =
    "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 3/3 4/4\n";

CliResult renderAlbedo(const TempDir& dir, const std::string& model, const std::string& out) {
  return runMontecl({"render", dir.file(model), "-o", dir.file(out), "--width", "12", "--height", "12", "--spp", "1",
                     "--integrator", "ao", "--aov", "albedo", "-q", "--overwrite"});
}

std::vector<float> albedoR(const std::string& exr) { return *montecl::readLayeredImage(exr).find("albedo.R"); }

std::size_t lines(const std::string& s) { return std::size_t(std::count(s.begin(), s.end(), '\n')); }

}  // namespace

TEST_CASE("textures: a name that differs in case is used with one warning; all missing ones in one line" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  std::filesystem::create_directory(dir.file("maps"));
  montecl_test::writeImage8(dir.file("maps/wood.png"), 4, 4, 3, [](int x, int y, int c) { return (x * 60 + y * 20 + c * 50) % 256; });
  dir.write("quad.obj", kQuad);
  dir.write("quad.mtl", "newmtl a\nmap_Kd maps/wood.png\nnewmtl b\nmap_Kd maps/wood.png\n");
  const CliResult exact = renderAlbedo(dir, "quad.obj", "exact.exr");
  REQUIRE(exact.exitCode == 0);
  // Folder and file in other cases (as written on a case-insensitive file system).
  dir.write("quad.mtl", "newmtl a\nmap_Kd MAPS/Wood.PNG\nnewmtl b\nmap_Kd maps/wood.png\n");
  const CliResult cased = renderAlbedo(dir, "quad.obj", "cased.exr");
  INFO(cased.err);
  CHECK(cased.exitCode == 0);
  CHECK(cased.err.find(dir.file("quad.mtl") + ": line 2: material 'a': map_Kd 'MAPS/Wood.PNG' not found as written; using '" +
                       dir.file("maps/wood.png") + "' (the names differ in case)") != std::string::npos);
  CHECK(lines(cased.err) == 1);
  CHECK(albedoR(dir.file("cased.exr")) == albedoR(dir.file("exact.exr")));

  // A glTF image URI in another case: the same, with one warning naming the image.
  std::string g = montecl_test::gltfText(montecl_test::tentMesh(), 1.0f, "tent.bin");
  g.insert(g.size() - 1, R"(,"images":[{"uri":"Maps/WOOD.png"}],"textures":[{"source":0}])");
  const std::string factor = R"("baseColorFactor":[1,1,1,1],)";
  g.insert(g.find(factor) + factor.size(), R"("baseColorTexture":{"index":0},)");
  dir.write("tent.bin", montecl_test::gltfBuffer(montecl_test::tentMesh()));
  dir.write("tent.gltf", g);
  const CliResult gltf = renderAlbedo(dir, "tent.gltf", "tent.exr");
  INFO(gltf.err);
  CHECK(gltf.exitCode == 0);
  CHECK(gltf.err.find(dir.file("tent.gltf") + ": images[0]: '" + dir.file("Maps/WOOD.png") + "' not found as written; using '" +
                      dir.file("maps/wood.png") + "'") != std::string::npos);

  // Three textures that exist in no case: one line naming every one, exit 2, nothing written.
  dir.write("quad.mtl", "newmtl a\nmap_Kd gone1.png\nmap_d gone2.png\nnewmtl b\nmap_Kd maps/gone3.png\n");
  const CliResult missing = renderAlbedo(dir, "quad.obj", "missing.exr");
  CHECK(missing.exitCode == 2);
  CHECK(lines(missing.err) == 1);
  CHECK(missing.err.find(dir.file("quad.mtl") + ": line 2: material 'a': map_Kd 'gone1.png': cannot open") != std::string::npos);
  CHECK(missing.err.find("also missing: line 3 map_d 'gone2.png', line 5 map_Kd 'maps/gone3.png' (3 textures missing)") !=
        std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("missing.exr")));
}

}  // namespace test_file_texture_paths
