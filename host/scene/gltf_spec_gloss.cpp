// gltf_spec_gloss.cpp: metalRoughFromSpecGloss (gltf_spec_gloss.h).
#include "scene/gltf_spec_gloss.h"

#include <algorithm>
#include <cmath>

namespace montecl {
namespace {

constexpr float kDielectricF0 = 0.04f;  // metal/rough's dielectric specular

float perceivedBrightness(glm::vec3 c) { return std::sqrt(0.299f * c.r * c.r + 0.587f * c.g * c.g + 0.114f * c.b * c.b); }

// The metallic that makes metal/rough's diffuse and specular brightness those of the
// specular-glossiness material: the positive root of a m^2 + b m + c = 0 (gltf_spec_gloss.h).
float solveMetallic(float diffuse, float specular, float oneMinusSpecularStrength) {
  if (specular < kDielectricF0) return 0.0f;
  const float a = kDielectricF0;
  const float b = diffuse * oneMinusSpecularStrength / (1.0f - kDielectricF0) + specular - 2.0f * kDielectricF0;
  const float c = kDielectricF0 - specular;
  const float d = std::max(b * b - 4.0f * a * c, 0.0f);
  return std::clamp((-b + std::sqrt(d)) / (2.0f * a), 0.0f, 1.0f);
}

}  // namespace

MetalRoughFactors metalRoughFromSpecGloss(glm::vec3 diffuse, glm::vec3 specular, float glossiness) {
  const float oneMinusSpecularStrength = 1.0f - std::max({specular.r, specular.g, specular.b});
  MetalRoughFactors out;
  out.metallic = solveMetallic(perceivedBrightness(diffuse), perceivedBrightness(specular), oneMinusSpecularStrength);
  const float eps = 1e-6f;
  const glm::vec3 fromDiffuse =
      diffuse * (oneMinusSpecularStrength / (1.0f - kDielectricF0) / std::max(1.0f - out.metallic, eps));
  const glm::vec3 fromSpecular = (specular - glm::vec3(kDielectricF0 * (1.0f - out.metallic))) * (1.0f / std::max(out.metallic, eps));
  out.base = glm::clamp(glm::mix(fromDiffuse, fromSpecular, out.metallic * out.metallic), glm::vec3(0.0f), glm::vec3(1.0f));
  out.roughness = std::clamp(1.0f - glossiness, 0.0f, 1.0f);
  return out;
}

}  // namespace montecl
