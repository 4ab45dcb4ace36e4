// layered_scene.h: the conformance set's scene for the layered material kinds (layered_scene.cpp).
#pragma once
#include "scene/scene.h"

namespace montecl {

// `base` (the rough-glass scene: a sphere of the last material, an occluder of material 2, under
// the environment) with the sphere made a coated_conductor (gold under a clear coat, two walks per
// evaluation) and the occluder a coated_diffuse: their random walks run under masks in the packet
// stages, so the set compares them bit for bit at every lane width.
Scene layeredScene(const Scene& base);

}  // namespace montecl
