// frame_params.h: fills the FrameParams constant block (camera basis, image size, settings) that
// every stage kernel reads.
#pragma once
#include "kernels/shared/types.h"
#include "scene/scene.h"

namespace montecl {

// shadowSlots: occlusion queries per pixel sample (1 for AO).
FrameParams makeFrameParams(const Camera& camera, const RenderSettings& settings, uint shadowSlots);

}  // namespace montecl
