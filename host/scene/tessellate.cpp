// tessellate.cpp: spheres and disks as triangles (tessellate.h), written in object space.
#include "scene/tessellate.h"

#include <cmath>

namespace montecl {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

void tessellateSphere(double r, std::vector<SceneTriangle>& out) {
  const int nPhi = kSphereSegments, nTheta = kSphereSegments / 2;
  auto corner = [&](int i, int j, glm::vec3& pos, glm::vec3& n, glm::vec2& uv) {
    const double theta = kPi * double(j) / nTheta;  // from the -z pole (v = 0) to +z, as pbrt's v
    const double phi = 2.0 * kPi * double(i) / nPhi;
    const glm::dvec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), -std::cos(theta));
    n = glm::vec3(d);
    pos = glm::vec3(d * r);
    uv = glm::vec2(float(double(i) / nPhi), float(double(j) / nTheta));
  };
  for (int j = 0; j < nTheta; ++j)
    for (int i = 0; i < nPhi; ++i) {
      SceneTriangle a{}, b{};
      glm::vec3 P[4], N[4];
      glm::vec2 UV[4];
      corner(i, j, P[0], N[0], UV[0]);
      corner(i + 1, j, P[1], N[1], UV[1]);
      corner(i + 1, j + 1, P[2], N[2], UV[2]);
      corner(i, j + 1, P[3], N[3], UV[3]);
      // P0 -> P1 runs east, P0 -> P3 north: cross(east, north) points outward.
      const int ta[3] = {0, 1, 2}, tb[3] = {0, 2, 3};
      for (int k = 0; k < 3; ++k) {
        a.v[k] = P[ta[k]], a.n[k] = N[ta[k]], a.uv[k] = UV[ta[k]];
        b.v[k] = P[tb[k]], b.n[k] = N[tb[k]], b.uv[k] = UV[tb[k]];
      }
      a.attributes = b.attributes = kHasNormals | kHasUv;
      if (j > 0) out.push_back(a);  // at the poles two corners meet: skip the zero-area half
      if (j + 1 < nTheta) out.push_back(b);
    }
}

void tessellateDisk(double r, double ri, double h, std::vector<SceneTriangle>& out) {
  const int n = kSphereSegments;
  for (int i = 0; i < n; ++i) {
    const double a0 = 2.0 * kPi * i / n, a1 = 2.0 * kPi * (i + 1) / n;
    const glm::vec3 o0(float(r * std::cos(a0)), float(r * std::sin(a0)), float(h));
    const glm::vec3 o1(float(r * std::cos(a1)), float(r * std::sin(a1)), float(h));
    const glm::vec3 i0(float(ri * std::cos(a0)), float(ri * std::sin(a0)), float(h));
    const glm::vec3 i1(float(ri * std::cos(a1)), float(ri * std::sin(a1)), float(h));
    auto tri = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
      SceneTriangle t{};
      t.v[0] = a, t.v[1] = b, t.v[2] = c;
      for (int k = 0; k < 3; ++k) {
        t.n[k] = glm::vec3(0, 0, 1);
        // pbrt's disk uv: u = phi / phimax, v = (radius - r) / (radius - innerradius)
        const double rr = std::sqrt(double(t.v[k].x) * t.v[k].x + double(t.v[k].y) * t.v[k].y);
        double phi = std::atan2(double(t.v[k].y), double(t.v[k].x));
        if (phi < 0) phi += 2 * kPi;
        t.uv[k] = glm::vec2(float(phi / (2 * kPi)), float((r - rr) / (r - ri)));
      }
      t.attributes = kHasNormals | kHasUv;
      out.push_back(t);
    };
    tri(i0, o0, o1);  // counter-clockwise seen from +z: the front is +z
    if (ri > 0.0) tri(i0, o1, i1);
  }
}

}  // namespace montecl
