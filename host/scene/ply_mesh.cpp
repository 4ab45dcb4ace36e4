// ply_mesh.cpp: loadPlyInto(): a PLY file (ply_reader.h) into a Scene. Reads vertex x y z,
// nx ny nz (kHasNormals, normalised) and texture coordinates (u v, s t or texture_u texture_v:
// kHasUv, OBJ's convention, not flipped); faces as index lists of any size (quads split along the
// shorter diagonal like tinyobjloader's, larger polygons fan-triangulated)
// and `tristrips` (alternating winding, -1 restarts). Every triangle gets the scene's default
// material (a scene file's "material" gives it another). Other elements and properties are one
// warning per kind.
#include <cmath>
#include <string>
#include <vector>

#include "scene/load_util.h"
#include "scene/mesh_loaders.h"
#include "scene/ply_reader.h"
#include "scene/scene.h"

namespace montecl {
namespace {

struct Vertices {
  int x = -1, y = -1, z = -1, nx = -1, ny = -1, nz = -1, u = -1, v = -1;  // property indices
  std::vector<glm::vec3> pos, normal;
  std::vector<glm::vec2> uv;
  std::vector<std::uint8_t> normalOk;  // 0 when the normal has zero length
};

int indexOf(const PlyElement& e, const std::string& name, bool list) {
  for (std::size_t k = 0; k < e.properties.size(); ++k)
    if (e.properties[k].name == name && e.properties[k].isList == list) return static_cast<int>(k);
  return -1;
}

void findVertexProperties(const std::string& file, const PlyElement& e, Vertices& v, KindWarnings& unused) {
  v.x = indexOf(e, "x", false), v.y = indexOf(e, "y", false), v.z = indexOf(e, "z", false);
  if (v.x < 0 || v.y < 0 || v.z < 0) loadFail(file, "element 'vertex'", "needs scalar properties x, y and z");
  v.nx = indexOf(e, "nx", false), v.ny = indexOf(e, "ny", false), v.nz = indexOf(e, "nz", false);
  if (v.nx < 0 || v.ny < 0 || v.nz < 0) v.nx = v.ny = v.nz = -1;
  for (const auto& uv : {std::pair<const char*, const char*>{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}}) {
    const int u = indexOf(e, uv.first, false), w = indexOf(e, uv.second, false);
    if (u >= 0 && w >= 0 && v.u < 0) v.u = u, v.v = w;
  }
  for (std::size_t k = 0; k < e.properties.size(); ++k) {
    const int i = static_cast<int>(k);
    if (i == v.x || i == v.y || i == v.z || i == v.nx || i == v.ny || i == v.nz || i == v.u || i == v.v) continue;
    unused.add("vertex " + e.properties[k].name, "element 'vertex'",
               "property '" + oneLine(e.properties[k].name, 40) + "' not used by montecl, ignored");
  }
}

float toFloat(double d, const std::string& file, const PlyRow& row, const char* what) {
  const float f = static_cast<float>(d);
  if (!std::isfinite(f))
    loadFail(file, "element 'vertex' row " + std::to_string(row.row),
             std::string(what) + " " + plyNumber(d) + " is not a finite float");
  return f;
}

void addVertex(const std::string& file, const PlyRow& r, Vertices& v) {
  const auto& s = r.scalars;
  v.pos.emplace_back(toFloat(s[v.x], file, r, "coordinate"), toFloat(s[v.y], file, r, "coordinate"),
                     toFloat(s[v.z], file, r, "coordinate"));
  if (v.nx >= 0) {
    glm::vec3 n(toFloat(s[v.nx], file, r, "normal"), toFloat(s[v.ny], file, r, "normal"),
                toFloat(s[v.nz], file, r, "normal"));
    const float len = glm::length(n);
    const bool ok = len > 0.0f && std::isfinite(len);
    v.normal.push_back(ok ? n / len : glm::vec3(0.0f));
    v.normalOk.push_back(ok);
  }
  if (v.u >= 0) v.uv.emplace_back(toFloat(s[v.u], file, r, "texture coordinate"), toFloat(s[v.v], file, r, "texture coordinate"));
}

struct Builder {
  const std::string& file;
  Scene& scene;
  const Vertices& v;
  std::uint32_t material;
  std::size_t zeroNormals = 0;

  std::string where(const PlyRow& r) const {
    return "element '" + oneLine(r.element->name, 40) + "' row " + std::to_string(r.row);
  }
  std::uint32_t index(double d, const PlyRow& r) const {
    // Float and double index lists are allowed by PLY: NaN or 1.5 must not become a vertex.
    if (std::isfinite(d) && d != std::floor(d))
      loadFail(file, where(r), "vertex index " + plyNumber(d) + " is not a whole number");
    if (!(d >= 0 && d < static_cast<double>(v.pos.size())))  // NaN fails too
      loadFail(file, where(r),
               "vertex index " + plyNumber(d) + " out of range (" + std::to_string(v.pos.size()) + " vertices)");
    return static_cast<std::uint32_t>(d);
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    SceneTriangle t{};
    const std::uint32_t idx[3] = {a, b, c};
    bool normals = !v.normal.empty();
    for (int k = 0; k < 3; ++k) {
      t.v[k] = v.pos[idx[k]];
      if (normals) normals = v.normalOk[idx[k]] != 0;
    }
    if (!v.normal.empty() && !normals) ++zeroNormals;
    for (int k = 0; k < 3; ++k) {
      if (normals) t.n[k] = v.normal[idx[k]];
      if (!v.uv.empty()) t.uv[k] = v.uv[idx[k]];
    }
    t.attributes = static_cast<std::uint8_t>((normals ? kHasNormals : 0) | (v.uv.empty() ? 0 : kHasUv));
    t.material = material;
    appendTriangle(scene, t);
  }
  void face(const std::vector<double>& list, const PlyRow& r) {
    if (list.size() < 3)
      loadFail(file, where(r),
               "face has " + std::to_string(list.size()) + " vertices (at least 3 needed)");
    if (list.size() == 4) {  // along the shorter diagonal (ties: 1-3), as the OBJ loader does
      const std::uint32_t i0 = index(list[0], r), i1 = index(list[1], r), i2 = index(list[2], r), i3 = index(list[3], r);
      const glm::vec3 e02 = v.pos[i2] - v.pos[i0], e13 = v.pos[i3] - v.pos[i1];
      const float sqr02 = e02.x * e02.x + e02.y * e02.y + e02.z * e02.z;
      const float sqr13 = e13.x * e13.x + e13.y * e13.y + e13.z * e13.z;
      if (sqr02 < sqr13) {
        triangle(i0, i1, i2);
        triangle(i0, i2, i3);
      } else {
        triangle(i0, i1, i3);
        triangle(i1, i2, i3);
      }
      return;
    }
    const std::uint32_t first = index(list[0], r);
    for (std::size_t k = 1; k + 1 < list.size(); ++k) triangle(first, index(list[k], r), index(list[k + 1], r));
  }
  void strip(const std::vector<double>& list, const PlyRow& r) {
    std::size_t start = 0;
    for (std::size_t k = 0; k <= list.size(); ++k) {
      if (k < list.size() && list[k] != -1.0) {
        index(list[k], r);  // checks the range
        continue;
      }
      for (std::size_t j = start; j + 2 < k; ++j) {
        const std::uint32_t a = index(list[j], r), b = index(list[j + 1], r), c = index(list[j + 2], r);
        if ((j - start) % 2 == 0) triangle(a, b, c);
        else triangle(b, a, c);
      }
      start = k + 1;
    }
  }
};

int faceListIndex(const PlyElement& e) {
  int k = indexOf(e, "vertex_indices", true);
  return k >= 0 ? k : indexOf(e, "vertex_index", true);
}

}  // namespace

void loadPlyInto(const std::string& path, Scene& scene, std::vector<std::string>* warnings) {
  const std::string text = readWholeFile(path);
  const PlyHeader header = parsePlyHeader(path, text);
  KindWarnings unused(path);
  Vertices v;
  bool sawVertex = false;
  for (const PlyElement& e : header.elements) {
    if (e.name == "vertex") {
      if (sawVertex) loadFail(path, "header", "two 'vertex' elements");
      sawVertex = true;
      findVertexProperties(path, e, v, unused);
    } else if (e.name == "face" || e.name == "tristrips") {
      if (!sawVertex) loadFail(path, "header", "element '" + e.name + "' before element 'vertex'");
      if (faceListIndex(e) < 0) loadFail(path, "element '" + e.name + "'", "needs a list property vertex_indices");
      for (const PlyProperty& p : e.properties)
        if (p.name != e.properties[std::size_t(faceListIndex(e))].name)
          unused.add(e.name + " " + p.name, "element '" + e.name + "'", "property '" + oneLine(p.name, 40) + "' not used by montecl, ignored");
    } else {
      unused.add("element " + e.name, "element '" + oneLine(e.name, 40) + "'", "element not used by montecl, ignored");
    }
  }
  if (!sawVertex) loadFail(path, "header", "no 'vertex' element");
  scene.inputFiles.push_back(path);
  const std::size_t before = scene.triangles.size(), droppedBefore = scene.degenerateDropped;
  Builder b{path, scene, v, defaultMaterialIndex(scene)};
  readPlyData(
      path, text, header, [](const PlyElement& e) { return e.name == "vertex" || e.name == "face" || e.name == "tristrips"; },
      [&](const PlyRow& r) {
        if (r.element->name == "vertex") return addVertex(path, r, v);
        const std::vector<double>& list = r.lists[std::size_t(faceListIndex(*r.element))];
        if (r.element->name == "face") b.face(list, r);
        else b.strip(list, r);
      });
  unused.flush(warnings);
  if (warnings && b.zeroNormals > 0)
    warnings->push_back(oneLine(path) + ": " + std::to_string(b.zeroNormals) +
                        " triangles have a zero-length normal at a corner, shaded with their flat normal");
  if (scene.triangles.size() == before)
    loadFail(path, "", "no triangles (" + std::to_string(scene.degenerateDropped - droppedBefore) +
                           " degenerate triangles dropped)");
}

}  // namespace montecl
