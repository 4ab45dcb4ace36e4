// frame_params.h: fills the FrameParams constant block (camera basis, image size, settings) that
// every stage kernel reads.
#pragma once
#include "kernels/shared/types.h"
#include "scene/scene.h"

namespace montecl {

// shadowSlots: occlusion queries per pixel sample (1 for AO).
FrameParams makeFrameParams(const Camera& camera, const RenderSettings& settings, uint shadowSlots);

// FrameParams::offsetScale for these triangles: the smallest power of two at or above their largest
// absolute coordinate, at most 1 (scenes of unit size or larger keep the unit offsets; a scene
// scaled down by 2^-k gets offsets scaled by exactly 2^-k).
float offsetScaleFor(const std::vector<SceneTriangle>& triangles);

}  // namespace montecl
