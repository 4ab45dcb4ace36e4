// mitsuba_shapes.h: Mitsuba shapes as montecl triangles: obj and ply (through montecl's loaders),
// rectangle, cube, and sphere and disk tessellated (tessellate.h). Reads a <shape>'s geometry
// properties; writes world-space triangles (material 0: the caller sets it).
#pragma once
#include <glm/gtc/matrix_transform.hpp>

#include <vector>

#include "scene/mitsuba_textures.h"

namespace montecl {

// False, with one warning, for a shape type montecl does not read (the render goes on without it).
// Texture coordinates come out in montecl's convention (v = 0 at the image's bottom row).
bool miShapeTriangles(MiContext& c, const MiProps& p, std::vector<SceneTriangle>& out);

}  // namespace montecl
