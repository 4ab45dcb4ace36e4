// pbrt_transforms.cpp: pbrt-v4's transform directives on the CTM (pbrt_transforms.h); each
// post-multiplies, so the transform given last applies first to a point, as in pbrt.
#include "scene/pbrt_transforms.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace montecl {

namespace {

// pbrt's LookAt: camera-from-world of a camera at eye looking at look, right = up x dir.
glm::dmat4 lookAt(const PbrtToken& d, glm::dvec3 eye, glm::dvec3 look, glm::dvec3 up) {
  const glm::dvec3 dir = look - eye;
  if (!(glm::length(dir) > 0.0)) pbrtFail(d.loc, "LookAt: the eye and the point looked at are the same");
  const glm::dvec3 f = glm::normalize(dir);
  if (!(glm::length(up) > 0.0) || glm::length(glm::cross(glm::normalize(up), f)) < 1e-12)
    pbrtFail(d.loc, "LookAt: the up vector is zero or along the viewing direction");
  const glm::dvec3 right = glm::normalize(glm::cross(glm::normalize(up), f));
  const glm::dvec3 newUp = glm::cross(f, right);
  glm::dmat4 worldFromCamera(1.0);
  worldFromCamera[0] = glm::dvec4(right, 0.0);
  worldFromCamera[1] = glm::dvec4(newUp, 0.0);
  worldFromCamera[2] = glm::dvec4(f, 0.0);
  worldFromCamera[3] = glm::dvec4(eye, 1.0);
  return glm::inverse(worldFromCamera);
}

}  // namespace

bool applyPbrtTransform(const PbrtToken& d, PbrtInput& in, glm::dmat4& ctm) {
  const std::string& w = d.text;
  if (w == "Identity") {
    ctm = glm::dmat4(1.0);
  } else if (w == "Translate") {
    const auto v = in.numbers(d, 3);
    ctm = glm::translate(ctm, glm::dvec3(v[0], v[1], v[2]));
  } else if (w == "Scale") {
    const auto v = in.numbers(d, 3);
    ctm = glm::scale(ctm, glm::dvec3(v[0], v[1], v[2]));
  } else if (w == "Rotate") {
    const auto v = in.numbers(d, 4);
    const glm::dvec3 axis(v[1], v[2], v[3]);
    if (!(glm::length(axis) > 0.0)) pbrtFail(d.loc, "Rotate: the axis must not be zero");
    ctm = glm::rotate(ctm, glm::radians(v[0]), glm::normalize(axis));
  } else if (w == "LookAt") {
    const auto v = in.numbers(d, 9);
    ctm = ctm * lookAt(d, glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5]), glm::dvec3(v[6], v[7], v[8]));
  } else if (w == "Transform" || w == "ConcatTransform") {
    // pbrt lists the matrix column by column (its translation in values 12..14), as glm stores it.
    const auto v = in.numbers(d, 16);
    const glm::dmat4 m = glm::make_mat4(v.data());
    ctm = w == "Transform" ? m : ctm * m;
  } else {
    return false;
  }
  return true;
}

}  // namespace montecl
