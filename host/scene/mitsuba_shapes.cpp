// mitsuba_shapes.cpp: Mitsuba shapes as world-space triangles (mitsuba_shapes.h): reads OBJ and PLY
// files through montecl's loaders, builds rectangles and cubes, tessellates spheres and disks.
#include "scene/mitsuba_shapes.h"

#include <utility>

#include "scene/load_util.h"
#include "scene/mesh_loaders.h"
#include "scene/tessellate.h"

namespace montecl {
namespace {

// Mitsuba's rectangle: [-1, 1]^2 at z = 0, front +z, uv (0, 0) at (-1, -1) in Mitsuba's convention.
void rectangle(const glm::dmat4& m, std::vector<SceneTriangle>& out) {
  const glm::dvec3 p[4] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const int tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (const auto& tri : tris) {
    SceneTriangle t{};
    for (int k = 0; k < 3; ++k) {
      t.v[k] = glm::vec3(m * glm::dvec4(p[tri[k]], 1.0));
      t.uv[k] = uv[tri[k]];
    }
    t.attributes = kHasUv;
    out.push_back(t);
  }
}

// Mitsuba's cube: [-1, 1]^3, each face a rectangle turned outwards.
void cube(std::vector<SceneTriangle>& out) {
  const double h = 1.5707963267948966;  // a quarter turn
  const glm::dmat4 id(1.0);
  const glm::dvec3 x(1, 0, 0), y(0, 1, 0);
  const glm::dmat4 faces[6] = {
      glm::translate(id, glm::dvec3(0, 0, 1)),
      glm::rotate(glm::translate(id, glm::dvec3(0, 0, -1)), 2 * h, y),
      glm::rotate(glm::translate(id, glm::dvec3(1, 0, 0)), h, y),
      glm::rotate(glm::translate(id, glm::dvec3(-1, 0, 0)), -h, y),
      glm::rotate(glm::translate(id, glm::dvec3(0, 1, 0)), -h, x),
      glm::rotate(glm::translate(id, glm::dvec3(0, -1, 0)), h, x),
  };
  for (const glm::dmat4& f : faces) rectangle(f, out);
}

// Triangles of an OBJ or PLY file in its own space; flipV: whether Mitsuba reads the file's v
// as it stands (then montecl's v, bottom-up, is 1 - v).
void meshFile(MiContext& c, const MiProps& p, std::vector<SceneTriangle>& out, bool& flipV) {
  const std::string name = p.getString("filename", "");
  if (name.empty()) mitsubaFail(p.loc, p.type + ": 'filename' is required");
  const std::string path = c.doc.resolve(name);
  const std::string problem = fileProblem(path);
  if (!problem.empty()) mitsubaFail(p.locOf("filename"), p.type + ": cannot open '" + oneLine(name, 100) + "': " + problem);
  Scene mesh;  // the loader's own scene: its materials are replaced by the shape's BSDF
  mesh.deferMissingTextures = true;  // an OBJ's MTL is not Mitsuba's business
  if (p.type == "obj") loadObjInto(path, mesh, &c.warnings);
  else loadPlyInto(path, mesh, &c.warnings);
  c.scene.inputFiles.push_back(path);
  for (const std::string& f : mesh.inputFiles) c.scene.inputFiles.push_back(f);
  out = std::move(mesh.triangles);
  // Mitsuba flips an OBJ's v by default (flip_tex_coords), landing where montecl's OBJ convention is.
  flipV = p.type == "obj" ? !p.getBool("flip_tex_coords", true) : true;
}

void place(std::vector<SceneTriangle>& tris, const glm::dmat4& m, bool flipNormals, bool flipV) {
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(m)));
  for (SceneTriangle& t : tris) {
    for (int k = 0; k < 3; ++k) {
      t.v[k] = glm::vec3(m * glm::dvec4(glm::dvec3(t.v[k]), 1.0));
      if (t.attributes & kHasNormals) {
        const glm::dvec3 n = glm::normalize(normalMatrix * glm::dvec3(t.n[k]));
        t.n[k] = glm::vec3(flipNormals ? -n : n);
      }
      if (flipV) t.uv[k].y = 1.0f - t.uv[k].y;
    }
    if (flipNormals) {  // the front is cross(v1 - v0, v2 - v0): swapping two corners turns it
      std::swap(t.v[1], t.v[2]);
      std::swap(t.n[1], t.n[2]);
      std::swap(t.uv[1], t.uv[2]);
    }
  }
}

}  // namespace

bool miShapeTriangles(MiContext& c, const MiProps& p, std::vector<SceneTriangle>& out) {
  glm::dmat4 m = p.getTransform("to_world");
  bool flipV = true;  // the built-in shapes' UVs are in Mitsuba's convention
  if (p.type == "obj" || p.type == "ply") {
    meshFile(c, p, out, flipV);
    if (p.getBool("face_normals", false))
      for (SceneTriangle& t : out) t.attributes = std::uint8_t(t.attributes & ~kHasNormals);
  } else if (p.type == "rectangle") {
    rectangle(glm::dmat4(1.0), out);
  } else if (p.type == "cube") {
    cube(out);
  } else if (p.type == "sphere") {
    const double r = p.getFloat("radius", 1.0);
    if (!(r > 0.0)) mitsubaFail(p.locOf("radius"), "sphere: 'radius' must be > 0");
    const std::optional<glm::dvec3> centre = p.getPoint("center");
    tessellateSphere(r, out);
    if (centre) m = m * glm::translate(glm::dmat4(1.0), *centre);
  } else if (p.type == "disk") {
    tessellateDisk(1.0, 0.0, 0.0, out);
  } else {
    c.warn(p.loc, "shape \"" + oneLine(p.type, 40) + "\" not read by montecl (it reads obj, ply, rectangle, cube, sphere, disk), left out");
    return false;
  }
  if (std::abs(glm::determinant(glm::dmat3(m))) < 1e-300) mitsubaFail(p.locOf("to_world"), p.type + ": 'to_world' is singular");
  place(out, m, p.getBool("flip_normals", false), flipV);
  return true;
}

}  // namespace montecl
