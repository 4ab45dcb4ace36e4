// equal_area.cpp: pbrt-v4's equal-area octahedral environment maps (equal_area.h): reads a square
// map's pixels, writes a latitude-longitude map's.
#include "scene/equal_area.h"

#include <algorithm>
#include <cmath>

namespace montecl {

glm::dvec2 equalAreaSphereToSquare(const glm::dvec3& d) {
  // pbrt-v4's EqualAreaSphereToSquare, with atan itself where pbrt uses a polynomial for it
  // (within 2.3e-7 of it).
  const double x = std::abs(d.x), y = std::abs(d.y), z = std::abs(d.z);
  const double r = std::sqrt(std::max(0.0, 1.0 - z));
  const double a = std::max(x, y), b = a == 0.0 ? 0.0 : std::min(x, y) / a;
  double phi = std::atan(b) * 2.0 / 3.14159265358979323846;
  if (x < y) phi = 1.0 - phi;
  double v = phi * r, u = r - v;
  if (d.z < 0.0) {  // the southern hemisphere folds out to the corners
    std::swap(u, v);
    u = 1.0 - u;
    v = 1.0 - v;
  }
  u = std::copysign(u, d.x);
  v = std::copysign(v, d.y);
  return glm::dvec2(0.5 * (u + 1.0), 0.5 * (v + 1.0));
}

std::vector<glm::vec3> latLongFromEqualArea(const std::vector<glm::vec3>& square, int side, const glm::dmat3& mapFromWorld,
                                            int& width, int& height) {
  const int n = std::min(side, kMaxEqualAreaResample);
  width = 2 * n;
  height = n;
  const double pi = 3.14159265358979323846;
  std::vector<glm::vec3> out(std::size_t(width) * std::size_t(height));
  for (int y = 0; y < height; ++y) {
    const double theta = pi * (y + 0.5) / height;  // montecl: theta from +y, phi = 2 pi u
    for (int x = 0; x < width; ++x) {
      const double phi = 2.0 * pi * (x + 0.5) / width;
      const glm::dvec3 dir(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
      const glm::dvec2 uv = equalAreaSphereToSquare(glm::normalize(mapFromWorld * dir));
      const int sx = std::min(side - 1, std::max(0, int(uv.x * side)));
      const int sy = std::min(side - 1, std::max(0, int(uv.y * side)));
      out[std::size_t(y) * std::size_t(width) + std::size_t(x)] = square[std::size_t(sy) * std::size_t(side) + std::size_t(sx)];
    }
  }
  return out;
}

}  // namespace montecl
