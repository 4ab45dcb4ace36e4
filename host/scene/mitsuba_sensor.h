// mitsuba_sensor.h: Mitsuba's sensor (perspective, thinlens: to_world, fov and fov_axis), its film
// (hdrfilm width and height) and sampler (sample_count, seed), and the integrator (path, direct;
// max_depth in Mitsuba's convention, which is montecl's), as montecl's camera and render settings.
// Reads <sensor> and <integrator> elements; writes the camera, the render settings and, where
// Mitsuba's camera mirrors montecl's, the reflection of the world that shows Mitsuba's picture.
#pragma once
#include "scene/mitsuba_textures.h"

namespace montecl {

struct MiCamera {
  Camera camera;
  glm::dmat4 worldMirror{1.0};
  bool mirrored = false;
};

// No <sensor>: Mitsuba's defaults (at the origin looking along +z, fov 39.3 on x, 768 x 576).
MiCamera miSensor(MiContext& c, const MiElem* sensor);

void miIntegrator(MiContext& c, const MiElem& integrator, RenderSettings& r);

}  // namespace montecl
