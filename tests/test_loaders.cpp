// test_loaders.cpp: the mesh loaders' surface attributes and materials: OBJ vt/vn into
// SceneTriangle::uv/n (+ attribute flags), MTL map_Kd/map_d/Ks/Ns into MaterialDesc (texture paths
// beside the MTL, missing textures and out-of-range values as InputError with the MTL line), and
// one warning per kind of statement montecl does not use.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace test_file_loaders {  // keeps this file's helpers apart in a unity batch

using montecl::InputError;
using montecl::Scene;
using montecl_test::TempDir;

namespace {

Scene loadObj(const std::string& path, std::vector<std::string>* warnings = nullptr) {
  Scene s;
  std::vector<std::string> w;
  montecl::loadObjInto(path, s, warnings ? warnings : &w);
  return s;
}

std::string objError(const std::string& path) {
  try {
    loadObj(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::size_t countContaining(const std::vector<std::string>& lines, const std::string& needle) {
  return static_cast<std::size_t>(
      std::count_if(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(needle) != std::string::npos; }));
}

// A quad (two triangles) with vt on both, vn on the first only (not unit length).
const char* kQuadObj =
    "mtllib m.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "vn 0 0 2\nvn 0 3 4\n"
    "usemtl tex\n"
    "f 1/1/1 2/2/1 3/3/2\n"
    "f 1/1 3/3 4/4\n";

}  // namespace

TEST_CASE("OBJ: vt and vn go to uv/n per corner, normals normalised, flags only where every corner has them" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("q.obj", kQuadObj);
  dir.write("m.mtl", "newmtl tex\nKd 1 1 1\n");
  Scene s = loadObj(dir.file("q.obj"));
  REQUIRE(s.triangles.size() == 2);
  const montecl::SceneTriangle& a = s.triangles[0];
  const montecl::SceneTriangle& b = s.triangles[1];
  CHECK(a.attributes == (montecl::kHasNormals | montecl::kHasUv));
  CHECK(b.attributes == montecl::kHasUv);
  CHECK(a.n[0] == glm::vec3(0, 0, 1));
  CHECK(a.n[1] == glm::vec3(0, 0, 1));
  CHECK(a.n[2].y == doctest::Approx(0.6f));
  CHECK(a.n[2].z == doctest::Approx(0.8f));
  CHECK(a.uv[1] == glm::vec2(1, 0));
  CHECK(a.uv[2] == glm::vec2(1, 1));
  CHECK(b.uv[2] == glm::vec2(0, 1));
  CHECK(b.n[0] == glm::vec3(0.0f));

  // A file without vt/vn: no flags.
  dir.write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  CHECK(loadObj(dir.file("plain.obj")).triangles[0].attributes == 0);
  // A zero-length vn: that face has no normals, and a warning says so.
  dir.write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n");
  std::vector<std::string> warnings;
  CHECK(loadObj(dir.file("zero.obj"), &warnings).triangles[0].attributes == 0);
  CHECK(countContaining(warnings, "zero-length vn") == 1);
  // vt/vn indices out of range: those faces lose them, with one warning.
  dir.write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\nf 1//-2 2//1 3//1\n");
  warnings.clear();
  Scene r = loadObj(dir.file("range.obj"), &warnings);
  INFO([&] { std::string all; for (auto& w : warnings) all += w + "\n"; return all; }());
  REQUIRE(r.triangles.size() == 2);
  CHECK(r.triangles[0].attributes == 0);
  CHECK(r.triangles[1].attributes == 0);
  CHECK(countContaining(warnings, "range.obj: line 6: face vn index -2 out of range (0 vn before it): those faces get no vt/vn (2 more faces like it)") == 1);
  CHECK(warnings.size() == 1);
}

TEST_CASE("OBJ: bad vt/vn values and indices are InputErrors with the line" * doctest::test_suite("cpu")) {
  TempDir dir;
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  struct Case {
    std::string obj, needle;
  } cases[] = {{tri + "vn 0 nan 1\nf 1//1 2//1 3//1\n", "line 4: normal coordinate 'nan' is not finite"},
               {tri + "vn 0 1\nf 1//1 2//1 3//1\n", "line 4: vn needs 3 numbers"},
               {tri + "vt 1e99 0\nf 1/1 2/1 3/1\n", "line 4: texture coordinate '1e99' out of float range"},
               {tri + "vt x\nf 1/1 2/1 3/1\n", "line 4: bad texture coordinate 'x'"},
               {tri + "f 1/1/1/1 2 3\n", "line 4: bad face vertex '1/1/1/1'"}};
  for (const Case& c : cases) {
    dir.write("bad.obj", c.obj);
    const std::string message = objError(dir.file("bad.obj"));
    INFO(c.obj << " -> " << message);
    CHECK(message.find("bad.obj: " + c.needle) != std::string::npos);
  }
}

TEST_CASE("MTL: map_Kd/map_d are resolved beside the MTL, Ks/Ns read, Kd of 1 under a map without Kd (then Kd + Ks scaled to 1)" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  std::filesystem::create_directories(dir.file("mtl/tex"));
  dir.write("q.obj", std::string(kQuadObj).replace(0, 12, "mtllib mtl/m.mtl"));
  dir.write("mtl/m.mtl",
            "newmtl tex\nKs 0.25 0.5 1\nNs 80\nmap_Kd tex/wood.png\nmap_d tex\\mask.png\n"
            "newmtl plain\nKd 0.2 0.3 0.4\nmap_Kd tex/wood.png\n");
  dir.write("mtl/tex/wood.png", "not read here");
  dir.write("mtl/tex/mask.png", "not read here");
  Scene s = loadObj(dir.file("q.obj"));
  REQUIRE(s.materials.size() == 2);
  const montecl::MaterialDesc& m = s.materials[0];
  CHECK(m.albedoTexture == dir.file("mtl/tex/wood.png"));
  CHECK(m.alphaTexture == dir.file("mtl/tex/mask.png"));  // the backslash name, found with a slash
  // Kd 1 (the map's default) + Ks exceeds 1 in blue: both scaled by 1 / 2 (energy conservation).
  CHECK(m.albedo == glm::vec3(0.5f));
  CHECK(m.specular == glm::vec3(0.125f, 0.25f, 0.5f));
  CHECK(m.specularExponent == 80.0f);
  CHECK(s.materials[1].albedo == glm::vec3(0.2f, 0.3f, 0.4f));
  CHECK(s.materials[1].specularExponent == 0.0f);
  CHECK(s.materials[1].alphaTexture.empty());
  // The textures are inputs of the render (once each).
  CHECK(std::count(s.inputFiles.begin(), s.inputFiles.end(), dir.file("mtl/tex/wood.png")) == 1);
}

TEST_CASE("MTL: missing textures, Ks outside [0, 1] and negative Ns name the MTL, its line and the key" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("q.obj", kQuadObj);
  struct Case {
    std::string mtl, needle;
  } cases[] = {{"newmtl tex\nKd 1 1 1\nmap_Kd gone.png\n", "m.mtl: line 3: material 'tex': map_Kd 'gone.png': cannot open"},
               {"# c\nnewmtl tex\nmap_d gone.png\n", "m.mtl: line 3: material 'tex': map_d 'gone.png': cannot open"},
               {"newmtl tex\nKs 0.5 1.5 0\n", "m.mtl: line 2: material 'tex': Ks components must be in [0, 1]"},
               {"newmtl tex\nKs -0.1 0 0\n", "m.mtl: line 2: material 'tex': Ks"},
               {"newmtl tex\n\nNs -3\n", "m.mtl: line 3: material 'tex': Ns must be finite and >= 0"},
               {"newmtl tex\nKe 1 -1 1\n", "m.mtl: line 2: material 'tex': Ke must be finite and >= 0"}};
  for (const Case& c : cases) {
    dir.write("m.mtl", c.mtl);
    const std::string message = objError(dir.file("q.obj"));
    INFO(c.mtl << " -> " << message);
    CHECK(message.find(c.needle) != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
  }
}

TEST_CASE("MTL: one warning per kind of unused statement, naming the MTL and the first line" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("q.obj", kQuadObj);
  dir.write("m.mtl",
            "newmtl tex\nKa 0 0 0\nillum 2\nNi 1.5\nd 0.5\ndisp n.png\nmap_Ns n.png\nmap_Ks s.png\n"
            "d 1\n"
            "newmtl other\nKa 1 1 1\nillum 1\nmap_Kd -s 2 2 1 t.png\n");
  dir.write("t.png", "x");
  std::vector<std::string> warnings;
  loadObj(dir.file("q.obj"), &warnings);
  INFO([&] { std::string all; for (auto& w : warnings) all += w + "\n"; return all; }());
  CHECK(countContaining(warnings, "m.mtl: line 2: 'Ka' (ambient colour) not used by montecl, ignored (1 more like it; -v lists them)") == 1);
  CHECK(countContaining(warnings, "m.mtl: line 3: 'illum' (illumination model) not used") == 1);
  CHECK(countContaining(warnings, "'Ni'") == 1);
  CHECK(countContaining(warnings, "m.mtl: line 5: 'd' (constant opacity) not used") == 1);
  CHECK(countContaining(warnings, "'disp' (displacement map)") == 1);
  CHECK(countContaining(warnings, "'map_Ns' (exponent texture)") == 1);
  CHECK(countContaining(warnings, "'map_Ks' (specular texture)") == 1);
  CHECK(countContaining(warnings, "m.mtl: line 13: texture option '-s'") == 1);
  CHECK(warnings.size() == 8);  // d 1 says nothing montecl ignores
  // Nothing unused, nothing said.
  dir.write("m.mtl", "newmtl tex\nKd 0.8 0.8 0.8\nKs 0.1 0.1 0.1\nNs 10\nKe 0 0 0\nd 1\n");
  warnings.clear();
  loadObj(dir.file("q.obj"), &warnings);
  CHECK(warnings.empty());
}

TEST_CASE("OBJ: statements montecl does not use are one warning per kind; used ones say nothing" *
          doctest::test_suite("cpu")) {
  TempDir dir;
  dir.write("u.obj",
            "o thing\ng part\ns 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\nl 2 3\np 1\n"
            "cstype bezier\ncurv 0 1 1 2\nusemap tex\n");
  std::vector<std::string> warnings;
  loadObj(dir.file("u.obj"), &warnings);
  INFO([&] { std::string all; for (auto& w : warnings) all += w + "\n"; return all; }());
  CHECK(warnings.size() == 5);
  CHECK(countContaining(warnings, "u.obj: line 8: 'l' (lines) not rendered by montecl, ignored (1 more like it; -v lists them)") == 1);
  CHECK(countContaining(warnings, "u.obj: line 10: 'p' (points)") == 1);
  CHECK(countContaining(warnings, "u.obj: line 11: free-form geometry ('cstype') not rendered by montecl, ignored (1 more like it; -v lists them)") == 1);
  CHECK(countContaining(warnings, "u.obj: line 13: 'usemap' not used") == 1);
  CHECK(countContaining(warnings, "u.obj: line 3: smoothing groups ('s') without vn") == 1);
  // With vn, smoothing groups say nothing; nor do o, g, s off.
  dir.write("n.obj", "o a\ng b\ns 1\ns off\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n");
  warnings.clear();
  loadObj(dir.file("n.obj"), &warnings);
  CHECK(warnings.empty());
}

}  // namespace test_file_loaders
