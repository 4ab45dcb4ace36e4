// value_limits.h: the largest and smallest light and material values the kernels can represent,
// checked by every loader at load time so that a value past them is one line naming the file and
// key, not a black image or a failure after the render. Pure; reads and writes nothing.
#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"

namespace montecl {

// A light's intensity or irradiance (and a sun's radiance) per component. A sample's value squared
// is the film's variance in float (at most 3.4e38): 1e15 leaves a factor 1e4 for 1/d^2 and the
// BSDF before that overflows.
constexpr double kMaxLightValue = 1e15;
// The smallest sun disk, in degrees of angular diameter: the kernels sample its cone and divide by
// its solid angle in float; 1e-4 degrees is a solid angle of 2.4e-12 sr.
constexpr double kMinSunDegrees = 1e-4;
// Conductor eta and k per component: the exact Fresnel squares their squares in float; real
// metals are below 100.
constexpr double kMaxConductorIndex = 1e4;
constexpr const char* kConductorIndexReason = "the exact Fresnel squares its square in float";
// A texture transform's offset and scale: past 2^24 a float UV holds no fraction, so no texel
// position (1e6 keeps 1/16 of a unit).
constexpr double kMaxTextureTransform = 1e6;

// World coordinates of placed instances: the BVH takes lengths of world boxes in float, whose
// squares pass float range (3.4e38) at about 1.8e19.
constexpr double kMaxWorldCoordinate = 1e18;
// The inverse of an instance's placement (world to object): a ray enters an instance as its world
// direction times it, and the traversal squares that direction's length in float. Scaled by 1e-20
// along one axis, an instance lost 16 of 256 pixels its flattened copy kept.
constexpr double kMaxInverseScale = 1e18;

// A value past its limit: the key it concerns (relative to the light: "intensity", "angle") and
// what is wrong; `what` is empty when there is none.
struct ValueProblem {
  std::string key, what;
  explicit operator bool() const { return !what.empty(); }
};

// The light's colour times its intensity (computed in double, before it is stored as a float)
// against kMaxLightValue, and for a sun its angle and radiance E / (pi sin^2 alpha). colourKey
// names the colour's key ("intensity", "irradiance", "color").
ValueProblem lightValueProblem(PunctualKind kind, const glm::dvec3& colour, double angleDegrees,
                               const std::string& colourKey);

// "" when the placement m (object to world) keeps the corners of an object-space box within
// kMaxWorldCoordinate and its inverse's entries (world to object) within kMaxInverseScale; else
// what is wrong ("moves vertices to 2e+19, past 1e+18 ...").
std::string placementProblem(const glm::dmat4& m, const std::vector<glm::vec3>& corners);

// "" when each component of v is finite and at most limit in magnitude, else "<v> is past <limit>:
// <reason>".
std::string magnitudeProblem(const glm::dvec3& v, double limit, const std::string& reason);

}  // namespace montecl
