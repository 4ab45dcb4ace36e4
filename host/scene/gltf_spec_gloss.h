// gltf_spec_gloss.h: glTF's KHR_materials_pbrSpecularGlossiness factors converted to the
// metallic-roughness model (what montecl's metal_rough kind draws). Pure arithmetic on the factors;
// reads and writes nothing else.
// The extension's BRDF has a diffuse colour c_diff = diffuse x (1 - max(specular)) and a specular
// F0 = specular; metal/rough has c_diff = base (1 - 0.04)(1 - metallic) and F0 = mix(0.04, base,
// metallic). Equating the two (for the perceived brightness of the colours) gives a quadratic in
// metallic, whose root is the metallic; the base colour is then the diffuse's or the specular's
// (blended by metallic^2 where both apply); roughness = 1 - glossiness. This is the conversion of
// Khronos' glTF sample viewer and of Babylon.js and glTF-Transform: exact for grey colours (a
// metal/rough material converted to specular-glossiness and back is itself, to float rounding),
// an approximation for coloured ones, and per factor only (textures: gltf_material.cpp).
#pragma once
#include <glm/glm.hpp>

namespace montecl {

struct MetalRoughFactors {
  glm::vec3 base{1.0f};
  float metallic = 1.0f, roughness = 1.0f;
};

// diffuse: diffuseFactor's RGB, specular: specularFactor, glossiness: glossinessFactor.
MetalRoughFactors metalRoughFromSpecGloss(glm::vec3 diffuse, glm::vec3 specular, float glossiness);

}  // namespace montecl
