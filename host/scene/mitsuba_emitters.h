// mitsuba_emitters.h: Mitsuba emitters as montecl lights: `area` (a shape's emission), `constant`
// and `envmap` (the environment), `point`, `spot`, `directional`. Reads <emitter> elements; writes
// Scene::lights, Scene::environment, or the emission of the shape's material.
#pragma once
#include "scene/mitsuba_textures.h"

namespace montecl {

// An area emitter of a shape: its radiance (a constant, or a texture's file times 1).
struct MiAreaLight {
  glm::vec3 radiance{0.0f};
  std::string texture;
  TextureSampling sampling;
};
MiAreaLight miAreaEmitter(MiContext& c, const MiElem& emitter);

// An emitter at the scene's top level (an `area` there is an error: it belongs in a shape).
void miEmitter(MiContext& c, const MiElem& emitter);

}  // namespace montecl
