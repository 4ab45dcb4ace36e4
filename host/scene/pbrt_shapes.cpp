// pbrt_shapes.cpp: pbrt-v4 shapes as triangles (pbrt_shapes.h): reads Shape parameters and PLY
// files, writes object-space triangles and places them.
#include "scene/pbrt_shapes.h"

#include <cmath>
#include <utility>

#include "scene/load_util.h"
#include "scene/mesh_loaders.h"
#include "scene/tessellate.h"

namespace montecl {
namespace {

// Triangles from indexed positions with optional normals and uvs (pbrt's trianglemesh).
void indexedTriangles(const PbrtParams& p, const std::vector<double>& P, const std::vector<double>& N,
                      const std::vector<double>& uv, const std::vector<std::size_t>& idx,
                      std::vector<SceneTriangle>& out) {
  const std::size_t nv = P.size() / 3;
  if (!N.empty() && N.size() != P.size())
    pbrtFail(p.loc, "'normal N' has " + std::to_string(N.size() / 3) + " normals for " + std::to_string(nv) + " points");
  if (!uv.empty() && uv.size() / 2 != nv)
    pbrtFail(p.loc, "'point2 uv' has " + std::to_string(uv.size() / 2) + " coordinates for " + std::to_string(nv) + " points");
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    SceneTriangle tri{};
    bool normals = !N.empty();
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = idx[t + std::size_t(k)];
      tri.v[k] = glm::vec3(float(P[3 * i]), float(P[3 * i + 1]), float(P[3 * i + 2]));
      if (normals) {
        const glm::vec3 n = glm::vec3(N[3 * i], N[3 * i + 1], N[3 * i + 2]);
        const float len = glm::length(n);
        if (!(len > 0.0f) || !std::isfinite(len)) normals = false;
        else tri.n[k] = n / len;
      }
      if (!uv.empty()) tri.uv[k] = glm::vec2(float(uv[2 * i]), float(uv[2 * i + 1]));
    }
    tri.attributes = std::uint8_t((normals ? kHasNormals : 0) | (uv.empty() ? 0 : kHasUv));
    out.push_back(tri);
  }
}

std::vector<std::size_t> checkedIndices(const PbrtParams& p, const std::vector<double>& raw, std::size_t nv, int group) {
  std::vector<std::size_t> idx;
  idx.reserve(raw.size());
  const PbrtParam* param = p.find("indices");
  for (double d : raw) {
    if (!(d >= 0.0 && d < double(nv)))
      // A huge or NaN index is printed as a double: converting it to an integer is undefined.
      pbrtFail(param->loc, "'integer indices': index " +
                               (std::fabs(d) < 1e15 ? std::to_string(static_cast<long long>(d)) : std::to_string(d)) +
                               " out of range (" + std::to_string(nv) + " points)");
    idx.push_back(std::size_t(d));
  }
  if (idx.size() % std::size_t(group) != 0)
    pbrtFail(param->loc, "'integer indices': " + std::to_string(idx.size()) + " indices, not a multiple of " + std::to_string(group));
  return idx;
}

void triangleMesh(const PbrtParams& p, std::vector<SceneTriangle>& out) {
  const std::vector<double> P = p.getNumbers("P", {"point3", "point"}, 3);
  if (P.empty()) pbrtFail(p.loc, "trianglemesh: 'point3 P' is required");
  std::vector<double> raw = p.getNumbers("indices", {"integer"}, 1);
  if (raw.empty()) {
    if (P.size() != 9) pbrtFail(p.loc, "trianglemesh: 'integer indices' is required unless there are exactly 3 points");
    raw = {0, 1, 2};
  }
  const std::vector<size_t> idx = checkedIndices(p, raw, P.size() / 3, 3);
  indexedTriangles(p, P, p.getNumbers("N", {"normal", "normal3"}, 3), p.getNumbers("uv", {"point2", "float"}, 2), idx, out);
}

// Each patch (p00, p10, p01, p11) as the triangles (p00, p10, p11) and (p00, p11, p01): the side
// of cross(p10 - p00, p01 - p00), pbrt's dpdu x dpdv, for a flat convex patch.
void bilinearMesh(const PbrtParams& p, std::vector<SceneTriangle>& out) {
  const std::vector<double> P = p.getNumbers("P", {"point3", "point"}, 3);
  if (P.empty()) pbrtFail(p.loc, "bilinearmesh: 'point3 P' is required");
  std::vector<double> raw = p.getNumbers("indices", {"integer"}, 1);
  if (raw.empty()) {
    if (P.size() != 12) pbrtFail(p.loc, "bilinearmesh: 'integer indices' is required unless there are exactly 4 points");
    raw = {0, 1, 2, 3};
  }
  const std::vector<size_t> quads = checkedIndices(p, raw, P.size() / 3, 4);
  std::vector<std::size_t> idx;
  for (std::size_t q = 0; q < quads.size(); q += 4) {
    const std::size_t a = quads[q], b = quads[q + 1], c = quads[q + 2], d = quads[q + 3];
    idx.insert(idx.end(), {a, b, d, a, d, c});
  }
  indexedTriangles(p, P, p.getNumbers("N", {"normal", "normal3"}, 3), p.getNumbers("uv", {"point2", "float"}, 2), idx, out);
}

// pbrt's sphere (radius, full: zmin, zmax and phimax are warned about when given), outward normals.
void tessellateSphere(const PbrtParams& p, std::vector<SceneTriangle>& out) {
  const double r = p.getFloat("radius", 1.0);
  if (!(r > 0.0 && std::isfinite(r))) pbrtFail(p.loc, "sphere: 'float radius' must be > 0");
  tessellateSphere(r, out);
}

// pbrt's disk: radius, innerradius, at z = height, normal +z.
void tessellateDisk(const PbrtParams& p, std::vector<SceneTriangle>& out) {
  const double r = p.getFloat("radius", 1.0), ri = p.getFloat("innerradius", 0.0), h = p.getFloat("height", 0.0);
  if (!(r > 0.0 && std::isfinite(r))) pbrtFail(p.loc, "disk: 'float radius' must be > 0");
  if (!(ri >= 0.0 && ri < r)) pbrtFail(p.loc, "disk: 'float innerradius' must be in [0, radius)");
  tessellateDisk(r, ri, h, out);
}

}  // namespace

bool pbrtShapeTriangles(const std::string& type, const PbrtParams& params, const std::string& baseFile,
                        std::vector<SceneTriangle>& out, std::vector<std::string>& warnings,
                        std::vector<std::string>& plyInputs) {
  if (type == "trianglemesh") {
    triangleMesh(params, out);
  } else if (type == "bilinearmesh") {
    bilinearMesh(params, out);
  } else if (type == "loopsubdiv") {
    warnings.push_back(params.loc.str() + ": Shape \"loopsubdiv\": montecl does not subdivide; its control mesh is rendered");
    params.ignore("levels");
    triangleMesh(params, out);
  } else if (type == "sphere") {
    for (const char* partial : {"zmin", "zmax", "phimax"})
      if (params.find(partial))
        warnings.push_back(params.loc.str() + ": Shape \"sphere\": '" + partial + "' (a partial sphere) not read by montecl; the whole sphere is rendered");
    tessellateSphere(params, out);
  } else if (type == "disk") {
    if (params.find("phimax"))
      warnings.push_back(params.loc.str() + ": Shape \"disk\": 'phimax' (a partial disk) not read by montecl; the whole disk is rendered");
    tessellateDisk(params, out);
  } else if (type == "plymesh") {
    const std::string name = params.getString("filename", "");
    if (name.empty()) pbrtFail(params.loc, "plymesh: 'string filename' is required");
    const std::string path = besideFile(baseFile, name);
    const std::string problem = fileProblem(path);
    if (!problem.empty()) pbrtFail(params.find("filename")->loc, "plymesh: cannot open '" + oneLine(name, 100) + "': " + problem);
    if (lowerExtension(path) == ".gz")
      pbrtFail(params.find("filename")->loc, "plymesh: '" + oneLine(name, 100) + "' is compressed; montecl reads uncompressed PLY only (gunzip it)");
    Scene ply;  // the loader's own scene: its default material is replaced by the caller's
    loadPlyInto(path, ply, &warnings);
    plyInputs.push_back(path);
    for (SceneTriangle& t : ply.triangles) {
      t.material = 0;
      out.push_back(t);
    }
    for (const char* displacement : {"displacement", "edgelength"})
      if (params.find(displacement))
        warnings.push_back(params.loc.str() + ": Shape \"plymesh\": '" + displacement + "' (displacement) not read by montecl, ignored");
  } else {
    warnings.push_back(params.loc.str() + ": Shape \"" + oneLine(type, 40) +
                       "\" not read by montecl (it reads trianglemesh, plymesh, bilinearmesh, sphere, disk, "
                       "loopsubdiv), left out");
    for (const PbrtParam& p : params.list) p.used = true;  // one warning for the whole shape
    return false;
  }
  return true;
}

void placePbrtTriangles(std::vector<SceneTriangle>& tris, const glm::dmat4& m, bool reverse) {
  const glm::dmat3 lin(m);
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(lin));
  const bool swaps = glm::determinant(lin) < 0.0;
  for (SceneTriangle& t : tris) {
    glm::dvec3 v[3];
    for (int k = 0; k < 3; ++k) v[k] = glm::dvec3(m * glm::dvec4(glm::dvec3(t.v[k]), 1.0));
    const glm::dvec3 g = glm::cross(v[1] - v[0], v[2] - v[0]);
    glm::dvec3 want = (reverse != swaps) ? -g : g;
    if (t.attributes & kHasNormals) {
      glm::dvec3 sum(0.0);
      bool finite = true;
      for (int k = 0; k < 3; ++k) {
        glm::dvec3 n = glm::normalize(normalMatrix * glm::dvec3(t.n[k]));
        if (reverse) n = -n;
        t.n[k] = glm::vec3(n);
        finite = finite && std::isfinite(t.n[k].x) && std::isfinite(t.n[k].y) && std::isfinite(t.n[k].z);
        sum += n;
      }
      // A singular transform (Scale 1 1 0) has no normals' matrix: the flat normal then shades.
      if (!finite) t.attributes = std::uint8_t(t.attributes & ~kHasNormals);
      else if (glm::dot(want, sum) < 0.0) want = -want;
    }
    for (int k = 0; k < 3; ++k) t.v[k] = glm::vec3(v[k]);
    if (glm::dot(want, g) < 0.0) {
      std::swap(t.v[1], t.v[2]);
      std::swap(t.n[1], t.n[2]);
      std::swap(t.uv[1], t.uv[2]);
    }
  }
}

}  // namespace montecl
