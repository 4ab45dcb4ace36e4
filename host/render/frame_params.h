// frame_params.h: fills the FrameParams constant block (camera basis, image size, settings) that
// every stage kernel reads.
#pragma once
#include "kernels/shared/types.h"
#include "scene/scene.h"

namespace montecl {

// Light selection (render/light_table.h): each kind's share of light samples and the light
// records' ranges (FrameParams share<Kind>, <kind>First, <kind>Count, lightCount).
struct LightSelection {
  float shareEnvironment = 0.0f, shareArea = 0.0f, sharePoint = 0.0f, shareSpot = 0.0f;
  float shareDirectional = 0.0f, shareSun = 0.0f;
  uint lightCount = 0;
  uint pointFirst = 0, pointCount = 0, spotFirst = 0, spotCount = 0;
  uint directionalFirst = 0, directionalCount = 0, sunFirst = 0, sunCount = 0;
};

// What FrameParams holds besides the camera and the settings, gathered by the renderer first so
// that the frame is made in one place (defaults: no lights, no textures, unit offsets).
struct FrameExtras {
  uint shadowSlots = 1;     // occlusion queries per pixel sample (IntegratorDesc::shadowSlots)
  float offsetScale = 1.0f; // offsetScaleFor(the scene's triangles)
  uint emitterCount = 0;    // the emitter table (render/emitters.h) ...
  float emitterPower = 0.0f;
  bool emissionTextured = false;  // a material's emission is textured (FrameParams::emissionTextured)
  float4 environment{0.0f};  // ... and the environment (render/environment_table.h), for lit integrators
  uint envWidth = 0, envHeight = 0;
  float envRotateY = 0.0f;
  uint textureCount = 0;
  bool alphaTested = false;    // some triangle carries MCL_ATTR_ALPHA (FrameParams::alphaTested)
  bool packetAllRays = false;  // packetTraversalForAllRays(the BVH's wide node count)
  uint instanceCount = 0;      // Bvh::instances (a two-level BVH), 0: one level
  bool recordAovs = false;     // first-hit AOVs are recorded (FrameParams::recordAovs)
  bool countLanes = false;     // --profile: the shading stages count lanes (FrameParams::countLanes)
  LightSelection lights;
};

// FrameParams::packetAllRays: whether rays in any octants (direct lighting's BRDF rays, path
// tracing's bounces, AO and shadow queries) take the packet traversals too, as coherent ones do.
// In a BVH this small every ray enters most of its nodes, so a packet's rays visit about what each
// would alone and the packet tests them W at a time; in a large one they part ways near the root
// (measured: bench/journal/lanes.md, "Small trees" and "Packet occlusion queries").
bool packetTraversalForAllRays(std::size_t wideNodes);

FrameParams makeFrameParams(const Camera& camera, const RenderSettings& settings, const FrameExtras& extras);
inline FrameParams makeFrameParams(const Camera& camera, const RenderSettings& settings, uint shadowSlots) {
  FrameExtras extras;
  extras.shadowSlots = shadowSlots;
  return makeFrameParams(camera, settings, extras);
}

// FrameParams::offsetScale for these triangles: the smallest power of two at or above their largest
// absolute coordinate, at most 1 (scenes of unit size or larger keep the unit offsets; a scene
// scaled down by 2^-k gets offsets scaled by exactly 2^-k).
float offsetScaleFor(const std::vector<SceneTriangle>& triangles);
// The same for a scene's world-space geometry: its triangles, or with instances the world ones
// and the placed boxes of the instances (their object-space triangles say nothing of the world).
float offsetScaleForScene(const Scene& scene);

}  // namespace montecl
