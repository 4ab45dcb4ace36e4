// obj_mesh.cpp: loads one OBJ (+ its MTL files) into a Scene. The pre-scan (obj_scan.h) catches
// what tinyobjloader silently accepts; tinyobjloader then parses the same in-memory text,
// triangulates, and reads the materials (mtl_materials.h). Per corner: positions, `vn` normals
// (normalised; kHasNormals when all three corners have one of non-zero length) and `vt` texture
// coordinates (kHasUv when all three corners have one).
#include <tiny_obj_loader.h>

#include <cmath>
#include <set>
#include <sstream>

#include "scene/load_util.h"
#include "scene/mtl_materials.h"
#include "scene/obj_scan.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace montecl {
namespace {

const char* const kDefaultMaterialName = "<default>";

// std::streambuf over a string, so tinyobj parses the text already read without a copy.
struct MemoryBuf : std::streambuf {
  explicit MemoryBuf(std::string& s) { setg(&s[0], &s[0], &s[0] + s.size()); }
};

struct ObjData {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::vector<MtlFile> mtlFiles;  // the MTL files read
};

void addWarnings(const std::string& file, const std::string& text, std::vector<std::string>* warnings) {
  if (!warnings) return;
  std::set<std::string> seen;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty() || line == "." || !seen.insert(line).second) continue;
    if (seen.size() > 5) {
      warnings->push_back(oneLine(file) + ": more tinyobjloader warnings omitted");
      return;
    }
    warnings->push_back(oneLine(file) + ": " + oneLine(line));
  }
}

ObjData parseWithTinyObj(const std::string& file, std::string& text, std::vector<std::string>* warnings) {
  ObjData data;
  MemoryBuf buf(text);
  std::istream in(&buf);
  MtlReader mtl(file);
  std::string warn, err;
  bool ok = tinyobj::LoadObj(&data.attrib, &data.shapes, &data.materials, &warn, &err, &in, &mtl,
                             /*triangulate=*/true, /*default_vcols_fallback=*/false);
  if (!mtl.notRegular.empty()) loadFail(file, "mtllib", "cannot open '" + mtl.notRegular);
  if (!ok) loadFail(file, "", "cannot parse OBJ: " + err.substr(0, err.find('\n')));
  data.mtlFiles = std::move(mtl.files);
  if (warnings) {
    for (const std::string& m : mtl.missing)
      warnings->push_back(oneLine(file) + ": material file '" + oneLine(m) + "' not found, using default material");
  }
  // tinyobj's own missing-file and index lines duplicate montecl's; keep its other warnings.
  std::string rest;
  std::istringstream lines(warn + err);
  std::string line;
  while (std::getline(lines, line))
    if (line.find("Material file [") == std::string::npos && line.find("Failed to load material") == std::string::npos &&
        line.find("indices out of bounds") == std::string::npos)  // the pre-scan's warning says it
      rest += line + "\n";
  addWarnings(file, rest, warnings);
  return data;
}

// ---- Conversion -----------------------------------------------------------------------------

std::size_t countFaces(const ObjData& data) {
  std::size_t n = 0;
  for (const auto& s : data.shapes) n += s.mesh.num_face_vertices.size();
  return n;
}

// A face index of tinyobj's (0-based, -1 when absent) into an array of `count` entries.
bool inRange(int index, std::size_t count) { return index >= 0 && static_cast<std::size_t>(index) < count; }

// Fills n[]/uv[] of t from the corners' vn/vt; counts faces whose normals cannot be normalised.
void cornerAttributes(const tinyobj::attrib_t& a, const tinyobj::index_t* idx, SceneTriangle& t,
                      std::size_t& zeroNormals) {
  const std::size_t normals = a.normals.size() / 3, uvs = a.texcoords.size() / 2;
  bool hasN = true, hasUv = true;
  for (int k = 0; k < 3; ++k) {
    hasN = hasN && inRange(idx[k].normal_index, normals);
    hasUv = hasUv && inRange(idx[k].texcoord_index, uvs);
  }
  if (hasN) {
    for (int k = 0; k < 3; ++k) {
      const tinyobj::real_t* c = &a.normals[3 * static_cast<std::size_t>(idx[k].normal_index)];
      const glm::vec3 n(static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]));
      const float len = glm::length(n);
      if (!(len > 0.0f) || !std::isfinite(len)) hasN = false;
      t.n[k] = hasN ? n / len : glm::vec3(0.0f);
    }
    if (!hasN) {
      ++zeroNormals;
      for (glm::vec3& n : t.n) n = glm::vec3(0.0f);
    }
  }
  if (hasUv)
    for (int k = 0; k < 3; ++k) {
      const tinyobj::real_t* c = &a.texcoords[2 * static_cast<std::size_t>(idx[k].texcoord_index)];
      t.uv[k] = glm::vec2(static_cast<float>(c[0]), static_cast<float>(c[1]));
    }
  t.attributes = static_cast<std::uint8_t>((hasN ? kHasNormals : 0) | (hasUv ? kHasUv : 0));
}

void appendTriangles(const std::string& file, const ObjData& data, std::uint32_t materialBase, Scene& scene,
                     std::vector<std::string>* warnings) {
  const std::vector<tinyobj::real_t>& pos = data.attrib.vertices;
  const std::size_t vertexCount = pos.size() / 3;
  std::size_t zeroNormals = 0;
  scene.triangles.reserve(scene.triangles.size() + countFaces(data));
  for (const tinyobj::shape_t& shape : data.shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    std::size_t offset = 0;
    for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      std::size_t corners = mesh.num_face_vertices[f];
      if (corners != 3) loadFail(file, "shape '" + oneLine(shape.name, 60) + "'", "face was not triangulated");
      SceneTriangle t{};
      const tinyobj::index_t* idx = &mesh.indices[offset];
      for (int k = 0; k < 3; ++k) {
        int vi = idx[k].vertex_index;
        if (!inRange(vi, vertexCount))
          loadFail(file, "", "face index " + std::to_string(vi + 1) + " out of range (" +
                                 std::to_string(vertexCount) + " vertices)");
        const tinyobj::real_t* c = &pos[3 * static_cast<std::size_t>(vi)];
        t.v[k] = glm::vec3(static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]));
      }
      offset += corners;
      cornerAttributes(data.attrib, idx, t, zeroNormals);
      int mid = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
      bool hasMaterial = mid >= 0 && static_cast<std::size_t>(mid) < data.materials.size();
      t.material = hasMaterial ? materialBase + static_cast<std::uint32_t>(mid) : defaultMaterialIndex(scene);
      appendTriangle(scene, t);
    }
  }
  if (warnings && zeroNormals > 0)
    warnings->push_back(oneLine(file) + ": " + std::to_string(zeroNormals) +
                        " faces have a zero-length vn, shaded with their flat normal");
}

}  // namespace

std::uint32_t defaultMaterialIndex(Scene& scene) {
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const MaterialDesc& m = scene.materials[i];
    if (m.name == kDefaultMaterialName && m.albedo == glm::vec3(0.5f) && m.emission == glm::vec3(0.0f))
      return static_cast<std::uint32_t>(i);
  }
  MaterialDesc d;
  d.name = kDefaultMaterialName;
  scene.materials.push_back(d);
  return static_cast<std::uint32_t>(scene.materials.size() - 1);
}

void loadObjInto(const std::string& objPath, Scene& scene, std::vector<std::string>* warnings) {
  std::string text = readWholeFile(objPath);
  if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);  // UTF-8 byte order mark
  ObjScan scan = scanObjText(objPath, text);
  if (warnings && scan.unknownStatements > 0)
    warnings->push_back(oneLine(objPath) + ": " + lineWhere(scan.firstUnknownLine) + ": unknown OBJ statement '" +
                        scan.firstUnknown + "' ignored" +
                        (scan.unknownStatements > 1
                             ? " (" + std::to_string(scan.unknownStatements - 1) + " more unknown statements)"
                             : std::string()));
  scan.unused.flush(warnings);
  if (warnings && scan.badAttributeIndices > 0)
    warnings->push_back(oneLine(objPath) + ": " + scan.firstBadAttribute + ": those faces get no vt/vn" +
                        (scan.badAttributeIndices > 1
                             ? " (" + std::to_string(scan.badAttributeIndices - 1) + " more faces like it)"
                             : std::string()));
  ObjData data = parseWithTinyObj(objPath, text, warnings);
  scene.inputFiles.push_back(objPath);
  for (const MtlFile& f : data.mtlFiles) scene.inputFiles.push_back(f.path);
  std::size_t trianglesBefore = scene.triangles.size();
  std::size_t droppedBefore = scene.degenerateDropped;
  std::uint32_t materialBase = appendMtlMaterials(objPath, data.materials, data.mtlFiles, scene, warnings);
  appendTriangles(objPath, data, materialBase, scene, warnings);
  if (scene.triangles.size() == trianglesBefore)
    loadFail(objPath, "", "no triangles (" + std::to_string(scene.degenerateDropped - droppedBefore) +
                              " degenerate triangles dropped)");
}

}  // namespace montecl
