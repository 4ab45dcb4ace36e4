// light_table.h: light selection for next-event estimation across the light kinds
// (kernels/shared/light_kinds.h): the table of light records (point, spot, directional, sun; grouped
// by kind, each picked within its kind by power) and each kind's share of the light samples,
// proportional to its power, as pbrt estimates it: emitters pi * sum(area * luminance(Le)),
// point 4 pi luminance(I), spot 2 pi luminance(I) (1 - (cos beam + cos cutoff) / 2), directional
// and sun pi R^2 luminance(E), the environment 4 pi * pi R^2 * mean luminance(L) over the sphere (R: the
// scene's bounding-sphere radius). A scene with one kind of light gives that kind exactly 1, so
// its samples are those of a renderer without the others.
#pragma once
#include <vector>

#include "render/environment_table.h"
#include "render/frame_params.h"
#include "scene/scene.h"

namespace montecl {

struct LightTable {
  std::vector<LightRecord> records;  // empty when the scene has no point, spot or directional light
  LightSelection selection;          // copied into FrameParams (FrameExtras::lights)
};

// emitterPower: EmitterTable::totalPower (0 without emitters); environment: the scene's
// (radiance.w = 0: none). Without lit, nothing.
LightTable buildLightTable(const Scene& scene, float emitterPower, const EnvironmentTable& environment, bool lit);

}  // namespace montecl
