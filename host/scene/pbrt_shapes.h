// pbrt_shapes.h: pbrt-v4 shapes as montecl triangles: trianglemesh, bilinearmesh, plymesh (through
// montecl's PLY loader), loopsubdiv (its control mesh), and sphere and disk tessellated. Reads a
// Shape directive's parameters (and a PLY file); writes triangles in object space, then places
// them with pbrt's rules for which side is the front.
#pragma once
#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "scene/pbrt_params.h"
#include "scene/tessellate.h"
#include "scene/scene.h"

namespace montecl {

// Builds the object-space triangles of shape `type` (material index 0, to be set by the caller).
// False, with a warning, for a shape montecl does not read (curve, cylinder, ...): the render
// goes on without it. baseFile: the main scene file, whose folder resolves file names (as pbrt does). plyInputs receives the PLY files read.
bool pbrtShapeTriangles(const std::string& type, const PbrtParams& params, const std::string& baseFile,
                        std::vector<SceneTriangle>& out, std::vector<std::string>& warnings,
                        std::vector<std::string>& plyInputs);

// Places triangles by toWorld (points by it, normals by its inverse transpose, flipped when
// reverseOrientation) and orders their corners so that montecl's front, cross(v1 - v0, v2 - v0),
// is pbrt's surface normal: the corners' cross product, negated when reverseOrientation differs
// from whether toWorld mirrors, and turned to the side of the shading normals when the shape has
// them (pbrt's FaceForward).
void placePbrtTriangles(std::vector<SceneTriangle>& tris, const glm::dmat4& toWorld, bool reverseOrientation);

}  // namespace montecl
