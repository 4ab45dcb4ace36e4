// test_cli_formats.cpp: `montecl render` of bare mesh files and scene-file mesh entries in every
// format: the same model as OBJ, PLY (ASCII, binary little/big endian), .gltf and .glb renders
// bit-identical images (the loaders give identical triangles, so the deterministic renderer must
// too); a glTF camera frames a bare glTF; unknown formats are refused.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "mesh_files.h"

using montecl_test::PlyEncoding;
using montecl_test::runMontecl;
using montecl_test::TempDir;

namespace {

montecl::LayeredImage render(const TempDir& dir, const std::string& input, const std::string& out) {
  auto r = runMontecl({"render", dir.file(input), "-o", dir.file(out), "--width", "40", "--height", "30", "--spp", "4", "-q"});
  INFO(input << ": " << r.err);
  REQUIRE(r.exitCode == 0);
  return montecl::readLayeredImage(dir.file(out));
}

}  // namespace

TEST_CASE("cli: one model as OBJ, PLY (ASCII, LE, BE), .gltf and .glb renders bit-identical images" *
          doctest::test_suite("cli")) {
  TempDir dir;
  const montecl_test::MeshData tent = montecl_test::tentMesh();
  dir.write("tent.obj", montecl_test::objText(tent));
  dir.write("ascii.ply", montecl_test::plyText(tent, PlyEncoding::Ascii));
  dir.write("le.ply", montecl_test::plyText(tent, PlyEncoding::LittleEndian));
  dir.write("be.ply", montecl_test::plyText(tent, PlyEncoding::BigEndian));
  dir.write("tent.gltf", montecl_test::gltfText(tent, 0.5f, "tent.bin"));
  dir.write("tent.bin", montecl_test::gltfBuffer(tent));
  dir.write("tent.glb", montecl_test::glbBytes(tent, 0.5f));
  const montecl::LayeredImage ref = render(dir, "tent.obj", "obj.exr");
  double sum = 0.0;
  for (float v : ref.planes[0]) sum += v;
  CHECK(sum > 0.0);
  for (const char* input : {"ascii.ply", "le.ply", "be.ply", "tent.gltf", "tent.glb"}) {
    INFO(input);
    const montecl::LayeredImage img = render(dir, input, std::string(input) + ".exr");
    REQUIRE(img.channels == ref.channels);
    for (std::size_t c = 0; c < img.planes.size(); ++c) CHECK(img.planes[c] == ref.planes[c]);
  }
  // The same through scene-file entries, one per format, each moved by a transform (the images
  // of the two scene files must agree as well).
  nlohmann::json a = {{"camera", {{"position", {1, 3, 9}}, {"target", {1, 0.5, -1}}, {"fov_y", 50}, {"width", 40}, {"height", 30}}},
                      {"meshes", nlohmann::json::array()}, {"render", {{"spp", 4}}}};
  nlohmann::json b = a;
  const char* files[] = {"tent.obj", "be.ply", "tent.glb"};
  for (int i = 0; i < 3; ++i) {
    a["meshes"].push_back({{"file", files[i]}, {"transform", {{"translate", {4 * i - 4, 0, 0}}}}});
    b["meshes"].push_back({{"file", "tent.obj"}, {"transform", {{"translate", {4 * i - 4, 0, 0}}}}});
  }
  dir.write("a.json", a.dump());
  dir.write("b.json", b.dump());
  const montecl::LayeredImage ia = render(dir, "a.json", "a.exr"), ib = render(dir, "b.json", "b.exr");
  for (std::size_t c = 0; c < ia.planes.size(); ++c) CHECK(ia.planes[c] == ib.planes[c]);
}

TEST_CASE("cli: a bare glTF with a camera renders through it; -v prints that camera" * doctest::test_suite("cli")) {
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
