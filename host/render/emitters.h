// emitters.h: what emits, and the light-selection table for direct lighting: every triangle whose
// material emits, in input order (Emitter::tri: its canonical slot in the BVH's triangles), with
// a CDF proportional to area * luminance(Ke), or for a textured emitter area * the mean luminance
// of Ke x texture over the triangle. The one rule: a triangle emits when that weight is > 0 (a
// textured triangle whose emission is 0 everywhere on it is no emitter); the kernels sample the
// table with pick_emitter and sample_triangle (kernels/shared/lights.h, light_area.h).
#pragma once
#include <vector>

#include "bvh/bvh.h"
#include "kernels/shared/surface_texture.h"
#include "scene/scene.h"

namespace montecl {

struct EmitterTable {
  std::vector<Emitter> emitters;  // empty when nothing emits
  float totalPower = 0.0f;        // sum of area * luminance(Ke)
};

// Light-selection weight of a triangle of this area and emission: area * luminance(Ke); it emits
// when the weight is > 0.
double emitterWeight(float area, const glm::vec3& emission);

// The emission textures: the device materials (maps.x), the texture tables, and the attributes
// (BVH order) where each textured emitter's mean luminance is written (tv.w) for the kernels' pdfs.
struct EmissionTextures {
  const std::vector<Material>* materials = nullptr;
  TextureTables tables{};
  std::vector<TriangleShading>* shading = nullptr;
};

// Without textured (or for untextured materials): the weights of Ke alone.
EmitterTable buildEmitterTable(const Bvh& bvh, const std::vector<MaterialDesc>& materials,
                               const EmissionTextures* textured = nullptr);

// Whether any triangle of the scene emits, by the table's rule for Ke alone (the direct integrator
// renders black without one; an emission texture that is black everywhere is not looked at).
bool hasEmitter(const Scene& scene);

}  // namespace montecl
