// test_cli_formats.cpp: `montecl render` of bare mesh files in every format: the same model as
// OBJ, PLY (ASCII, binary big endian) and .glb renders
// bit-identical images (the loaders give identical triangles, so the deterministic renderer must
// too); a glTF camera frames a bare glTF. (Scene-file entries of every format: scenes/test/bad
// cases and test_gltf/test_mesh_entry.)
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "mesh_files.h"

namespace test_file_cli_formats {  // keeps this file's helpers apart in a unity batch

using montecl_test::PlyEncoding;
using montecl_test::runMontecl;
using montecl_test::TempDir;

namespace {

montecl::LayeredImage render(const TempDir& dir, const std::string& input, const std::string& out) {
  auto r = runMontecl({"render", dir.file(input), "-o", dir.file(out), "--width", "24", "--height", "16", "--spp", "2", "-q"});
  INFO(input << ": " << r.err);
  REQUIRE(r.exitCode == 0);
  return montecl::readLayeredImage(dir.file(out));
}

}  // namespace

TEST_CASE("cli: one model as bare OBJ, PLY (ASCII, big endian) and .glb renders bit-identical images" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const montecl_test::MeshData tent = montecl_test::tentMesh();
  dir.write("tent.obj", montecl_test::objText(tent));
  dir.write("ascii.ply", montecl_test::plyText(tent, PlyEncoding::Ascii));
  dir.write("be.ply", montecl_test::plyText(tent, PlyEncoding::BigEndian));
  dir.write("tent.glb", montecl_test::glbBytes(tent, 0.5f));
  const montecl::LayeredImage ref = render(dir, "tent.obj", "obj.exr");
  double sum = 0.0;
  for (float v : ref.planes[0]) sum += v;
  CHECK(sum > 0.0);
  // (Little-endian PLY and .gltf give the same triangles as these, exactly: test_ply, test_gltf.)
  for (const char* input : {"ascii.ply", "be.ply", "tent.glb"}) {
    INFO(input);
    const montecl::LayeredImage img = render(dir, input, std::string(input) + ".exr");
    REQUIRE(img.channels == ref.channels);
    for (std::size_t c = 0; c < img.planes.size(); ++c) CHECK(img.planes[c] == ref.planes[c]);
  }
}

TEST_CASE("cli: a bare glTF with a camera renders through it; -v prints that camera" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  nlohmann::json g = nlohmann::json::parse(montecl_test::gltfText(montecl_test::tentMesh(), 0.5f, ""));
  g["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"aspectRatio", 2.0}, {"znear", 0.1}}}}};
  g["nodes"].push_back({{"camera", 0}, {"translation", {1, 1, 6}}});
  g["scenes"][0]["nodes"] = {0, 1};
  dir.write("cam.gltf", g.dump());
  auto r = runMontecl({"render", dir.file("cam.gltf"), "-o", dir.file("cam.exr"), "--spp", "1", "-v", "--height", "20", "--width", "40"});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(r.err.find("\"position\": [1, 1, 6]") != std::string::npos);
  CHECK(r.err.find("\"target\": [1, 1, 5]") != std::string::npos);
}

}  // namespace test_file_cli_formats
