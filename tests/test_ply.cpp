// test_ply.cpp: the PLY loader (host/scene/ply_mesh.cpp, ply_reader.cpp): ASCII and binary
// (little and big endian) files give exactly the triangles of the same model as OBJ; texture
// coordinate names, polygon fans, triangle strips with -1 restarts; malformed files are one
// InputError line naming the file and where; unused elements and properties one warning per kind.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "cli_runner.h"
#include "mesh_files.h"
#include "scene/mesh_loaders.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace test_file_ply {  // keeps this file's helpers apart in a unity batch

using montecl::Scene;
using montecl_test::MeshData;
using montecl_test::PlyEncoding;
using montecl_test::TempDir;

namespace {

Scene loadPly(const std::string& path, std::vector<std::string>* warnings = nullptr) {
  Scene s;
  std::vector<std::string> w;
  montecl::loadPlyInto(path, s, warnings ? warnings : &w);
  return s;
}

std::string plyError(const std::string& path) {
  try {
    loadPly(path);
  } catch (const montecl::InputError& e) {
    return e.what();
  }
  return "";
}

void checkSameTriangles(const Scene& a, const Scene& b) {
  REQUIRE(a.triangles.size() == b.triangles.size());
  for (std::size_t i = 0; i < a.triangles.size(); ++i) {
    const montecl::SceneTriangle &x = a.triangles[i], &y = b.triangles[i];
    CHECK(x.attributes == y.attributes);
    for (int k = 0; k < 3; ++k) {
      CHECK(x.v[k] == y.v[k]);
      CHECK(x.n[k] == y.n[k]);
      CHECK(x.uv[k] == y.uv[k]);
    }
    CHECK(a.materials[x.material].albedo == b.materials[y.material].albedo);
  }
}

}  // namespace

TEST_CASE("PLY: ASCII, binary little and big endian give exactly the OBJ's triangles" * doctest::test_suite("cpu")) {
  TempDir dir;
  const MeshData tent = montecl_test::tentMesh();
  dir.write("tent.obj", montecl_test::objText(tent));
  Scene obj;
  montecl::loadObjInto(dir.file("tent.obj"), obj);
  REQUIRE(obj.triangles.size() == 4);
  REQUIRE(obj.triangles[0].attributes == (montecl::kHasNormals | montecl::kHasUv));
  const PlyEncoding encodings[] = {PlyEncoding::Ascii, PlyEncoding::LittleEndian, PlyEncoding::BigEndian};
  for (PlyEncoding e : encodings)
    for (const char* uv : {"u v", "s t", "texture_u texture_v"}) {
      INFO("encoding " << int(e) << ", uv names " << std::string(uv));
      dir.write("tent.ply", montecl_test::plyText(tent, e, uv));
      std::vector<std::string> warnings;
      Scene ply = loadPly(dir.file("tent.ply"), &warnings);
      checkSameTriangles(obj, ply);
      CHECK(warnings.empty());
      CHECK(ply.inputFiles == std::vector<std::string>{dir.file("tent.ply")});
    }
  // Without normals and UVs: no attribute flags.
  MeshData bare = tent;
  bare.normals.clear();
  bare.uvs.clear();
  dir.write("bare.ply", montecl_test::plyText(bare, PlyEncoding::BigEndian));
  for (const auto& t : loadPly(dir.file("bare.ply")).triangles) CHECK(t.attributes == 0);
}

TEST_CASE("PLY: tristrips with -1 restarts alternate the winding; polygons are fans; other types read" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  // A 3x2 grid of vertices in the xy plane; two strips (restart) over its two rows of quads.
  dir.write("strip.ply",
            "ply\nformat ascii 1.0\nelement vertex 9\nproperty double x\nproperty double y\nproperty double z\n"
            "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n0 2 0\n1 2 0\n2 2 0\n"
            "13 0 3 1 4 2 5 -1 3 6 4 7 5 8\n");
  Scene s = loadPly(dir.file("strip.ply"));
  REQUIRE(s.triangles.size() == 8);
  for (const auto& t : s.triangles) CHECK(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]).z < 0);  // 0,3,1: clockwise
  // A pentagon with ushort indices and a uint8 count, and char/short/uint coordinates.
  dir.write("poly.ply",
            "ply\r\nformat ascii 1.0\r\nelement vertex 5\r\nproperty char x\r\nproperty short y\r\nproperty uint z\r\n"
            "element face 1\r\nproperty list uint8 ushort vertex_index\r\nend_header\r\n"
            "0 0 0\r\n2 0 0\r\n3 1 0\r\n1 2 0\r\n-1 1 0\r\n5 0 1 2 3 4\r\n");
  Scene p = loadPly(dir.file("poly.ply"));
  CHECK(p.triangles.size() == 3);
  for (const auto& t : p.triangles) CHECK(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]).z > 0);
}

TEST_CASE("PLY: unused elements and properties are one warning per kind, naming the file" * doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("c.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
            "property uchar red\nproperty uchar green\nelement face 1\nproperty list uchar int vertex_indices\n"
            "property uchar flags\nelement edge 2\nproperty int vertex1\nproperty int vertex2\nend_header\n"
            "0 0 0 255 0\n1 0 0 255 0\n0 1 0 255 0\n3 0 1 2 7\n0 1\n1 2\n");
  std::vector<std::string> warnings;
  CHECK(loadPly(dir.file("c.ply"), &warnings).triangles.size() == 1);
  INFO([&] { std::string all; for (auto& w : warnings) all += w + "\n"; return all; }());
  CHECK(warnings.size() == 4);
  for (const std::string& w : warnings) CHECK(w.find(dir.file("c.ply") + ": element '") == 0);
  CHECK(warnings[0].find("property 'red' not used by montecl") != std::string::npos);
  CHECK(warnings[3].find("element 'edge': element not used by montecl") != std::string::npos);
}

TEST_CASE("PLY: malformed files are one InputError line naming the file and where" * doctest::test_suite("cpu")) {
  TempDir dir;
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string faceHead = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string verts = "0 0 0\n1 0 0\n0 1 0\n";
  std::string binary = montecl_test::plyText(montecl_test::tentMesh(), PlyEncoding::LittleEndian);
  struct Case {
    std::string text, needle;
  } cases[] = {
      {"{\"camera\": 1}", "line 1: not a PLY file"},
      {"ply\nformat ascii 1.0\nelement vertex 3\n", "header: no 'end_header' line"},
      {"ply\nformat utf8 1.0\nend_header\n", "header line 2: unknown format 'utf8'"},
      {"ply\nformat ascii 2.0\nend_header\n", "header line 2: unsupported PLY version '2.0'"},
      {"ply\nformat ascii 1.0\nelement vertex -3\nend_header\n", "header line 3: bad element count '-3'"},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", "header line 3: property before any element"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty half x\nend_header\n", "header line 4: unknown type 'half'"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int i\nend_header\n", "header line 4: list length type must be an integer type"},
      {"ply\nformat ascii 1.0\nbogus\nend_header\n", "header line 3: unknown header keyword 'bogus'"},
      {"ply\nelement vertex 0\nend_header\n", "header: no 'format' line"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n" + faceHead + verts, "element 'vertex': needs scalar properties x, y and z"},
      {head + "element face 1\nproperty int i\nend_header\n" + verts + "0\n", "element 'face': needs a list property vertex_indices"},
      {head + faceHead + verts + "3 0 1 3\n", "element 'face' row 0: vertex index 3 out of range (3 vertices)"},
      {head + faceHead + verts + "3 0 1 -1\n", "element 'face' row 0: vertex index -1 out of range"},
      {head + faceHead + verts + "2 0 1\n", "element 'face' row 0: face has 2 vertices (at least 3 needed)"},
      {head + faceHead + "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", "element 'vertex' row 1: bad number 'x'"},
      {head + faceHead + "0 0 0\n1 1e39 0\n0 1 0\n3 0 1 2\n", "element 'vertex' row 1: coordinate"},
      {head + faceHead + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "element 'vertex' row 1: coordinate nan is not a finite float"},
      {head + faceHead + verts + "3 0 1.5 2\n", "element 'face' row 0: expected an integer"},
      {head + faceHead + verts, "element 'face': 1 rows cannot fit in the 1 bytes left"},
      {head + faceHead + verts + "3 0 1", "element 'face' row 0: truncated data"},
      {head + faceHead + verts + "3 0 1 2\n7\n", "end of data: unexpected data after the last element"},
      {head + faceHead + verts + "200 0 1 2\n", "element 'face' row 0: list length 200 longer than the data left"},
      {"ply\nformat ascii 1.0\nelement vertex 3000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
       "element 'vertex': 3000000000 rows cannot fit"},
      {binary.substr(0, binary.size() - 3), "element 'face' row 2: truncated data"},
      {head + faceHead + "0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n", "no triangles (1 degenerate triangles dropped)"},
      {"ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n", "header: element 'face' before element 'vertex'"},
  };
  for (const Case& c : cases) {
    dir.write("bad.ply", c.text);
    const std::string message = plyError(dir.file("bad.ply"));
    INFO(c.text.substr(0, 300) << "\n -> " << message);
    CHECK(message.find(dir.file("bad.ply") + ": " + c.needle) == 0);
    CHECK(message.find('\n') == std::string::npos);
  }
}

}  // namespace test_file_ply
