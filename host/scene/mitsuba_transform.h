// mitsuba_transform.h: a Mitsuba <transform> element (translate, rotate, scale, matrix, lookat,
// each applied after the ones before it) as a 4x4 matrix, column vectors.
#pragma once
#include <glm/glm.hpp>

#include "scene/mitsuba_xml.h"

namespace montecl {

// A transform that is one <lookat> and nothing else, kept as written: a camera made from it is the
// same, bit for bit, as a montecl camera given these three points.
struct MiLookAt {
  bool only = false;
  glm::dvec3 origin{0.0}, target{0.0, 0.0, 1.0}, up{0.0, 1.0, 0.0};
};

glm::dmat4 miTransform(const MiDocument& doc, const MiElem& transform, MiLookAt* lookAt = nullptr);

}  // namespace montecl
