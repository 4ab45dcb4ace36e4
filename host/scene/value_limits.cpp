// value_limits.cpp: the load-time rules of light and material values (value_limits.h). Pure.
#include "scene/value_limits.h"

#include <cmath>
#include <cstdio>

namespace montecl {
namespace {

std::string limitNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

std::string magnitudeProblem(const glm::dvec3& v, double limit, const std::string& reason) {
  for (int c = 0; c < 3; ++c)
    if (!(std::fabs(v[c]) <= limit))
      return limitNumber(v[c]) + " is past " + limitNumber(limit) + ": " + reason;
  return "";
}

std::string placementProblem(const glm::dmat4& m, const std::vector<glm::vec3>& corners) {
  for (const glm::vec3& c : corners) {
    const glm::dvec3 w(m * glm::dvec4(glm::dvec3(c), 1.0));
    if (std::string p = magnitudeProblem(w, kMaxWorldCoordinate, "the BVH's float box sizes would overflow");
        !p.empty())
      return "moves vertices to " + p;
  }
  const glm::dmat4 inv = glm::inverse(m);
  // The linear part against kMaxInverseScale; the translation (stored as a float) against float range.
  if (std::string p = magnitudeProblem(glm::dvec3(inv[3]), 3.4e38, "its inverse (world to object) leaves float range");
      !p.empty())
    return "has an inverse (world to object) entry " + p;
  for (int c = 0; c < 3; ++c)
    if (std::string p = magnitudeProblem(glm::dvec3(inv[c]), kMaxInverseScale,
                                         "rays entering the instance (world direction x inverse) pass float range "
                                         "when squared; scale the mesh by its \"transform\" instead");
        !p.empty())
      return "has an inverse (world to object) entry " + p;
  return "";
}

ValueProblem lightValueProblem(PunctualKind kind, const glm::dvec3& colour, double angleDegrees,
                               const std::string& colourKey) {
  const std::string range = "more than the film can hold (its square must fit a float)";
  if (std::string p = magnitudeProblem(colour, kMaxLightValue, range); !p.empty()) return {colourKey, p};
  if (kind != PunctualKind::Sun) return {};
  if (!(angleDegrees >= kMinSunDegrees))
    return {"angle", limitNumber(angleDegrees) + " degrees is below " + limitNumber(kMinSunDegrees) +
                         " (a narrower disk's solid angle leaves float range)"};
  const double pi = 3.14159265358979323846, s = std::sin(0.5 * angleDegrees * pi / 180.0);
  if (std::string p = magnitudeProblem(colour / (pi * s * s), kMaxLightValue, "the sun's radiance, " + range);
      !p.empty())
    return {"angle", limitNumber(angleDegrees) + " degrees with this irradiance: " + p};
  return {};
}

}  // namespace montecl
