// pbrt_transforms.h: pbrt-v4's transform directives on the current transformation matrix (CTM):
// Identity, Translate, Scale, Rotate, LookAt, Transform, ConcatTransform, each composed as pbrt
// composes them (the last one given applies first to a point).
#pragma once
#include <glm/glm.hpp>

#include "scene/pbrt_input.h"

namespace montecl {

// Applies directive d (its numbers read from in) to ctm; false when d is no transform directive.
bool applyPbrtTransform(const PbrtToken& d, PbrtInput& in, glm::dmat4& ctm);

}  // namespace montecl
