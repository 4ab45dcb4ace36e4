// mitsuba_transform.cpp: reads a Mitsuba <transform> element's steps into a matrix
// (mitsuba_transform.h); a malformed step is one error at its place.
#include "scene/mitsuba_transform.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cctype>
#include <cmath>

#include "scene/load_util.h"
#include "scene/mitsuba_props.h"

namespace montecl {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// A step's vector: value="x y z" (or one number, when `uniform`), else its x, y, z attributes
// (each `missing` when absent).
glm::dvec3 stepVector(const MiDocument& doc, const MiElem& e, double missing, bool uniform) {
  const MiLoc at = doc.loc(e);
  if (doc.hasAttr(e, "value")) {
    const std::vector<double> v = miNumbers(at, "<" + e.tag() + ">", doc.attr(e, "value"));
    if (v.size() == 1 && uniform) return glm::dvec3(v[0]);
    if (v.size() != 3) mitsubaFail(at, "<" + e.tag() + ">: 'value' must have 3 numbers");
    return glm::dvec3(v[0], v[1], v[2]);
  }
  glm::dvec3 out(missing);
  const char* axis[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i)
    if (doc.hasAttr(e, axis[i])) {
      const std::vector<double> v = miNumbers(at, std::string("<") + e.tag() + "> '" + axis[i] + "'", doc.attr(e, axis[i]));
      if (v.size() != 1) mitsubaFail(at, std::string("<") + e.tag() + ">: '" + axis[i] + "' must be one number");
      out[i] = v[0];
    }
  return out;
}

glm::dvec3 point3(const MiDocument& doc, const MiElem& e, const char* name, glm::dvec3 fallback) {
  if (!doc.hasAttr(e, name)) return fallback;
  const std::vector<double> v = miNumbers(doc.loc(e), std::string("<lookat> '") + name + "'", doc.attr(e, name));
  if (v.size() != 3) mitsubaFail(doc.loc(e), std::string("<lookat>: '") + name + "' must have 3 numbers");
  return glm::dvec3(v[0], v[1], v[2]);
}

// Mitsuba's look-at frame: columns left, up, forward and the origin (its camera looks along +z
// with +x to the image's left).
glm::dmat4 lookAtMatrix(const MiDocument& doc, const MiElem& e, MiLookAt& l) {
  l.origin = point3(doc, e, "origin", glm::dvec3(0.0));
  l.target = point3(doc, e, "target", glm::dvec3(0.0, 0.0, 1.0));
  l.up = point3(doc, e, "up", glm::dvec3(0.0, 1.0, 0.0));
  const glm::dvec3 dir = l.target - l.origin;
  if (!(glm::length(dir) > 0.0)) mitsubaFail(doc.loc(e), "<lookat>: 'origin' and 'target' are the same point");
  const glm::dvec3 f = glm::normalize(dir);
  const glm::dvec3 side = glm::cross(l.up, f);
  if (!(glm::length(side) > 1e-12 * glm::length(l.up))) mitsubaFail(doc.loc(e), "<lookat>: 'up' is parallel to the view direction");
  const glm::dvec3 left = glm::normalize(side);
  const glm::dvec3 up = glm::cross(f, left);
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(left, 0.0);
  m[1] = glm::dvec4(up, 0.0);
  m[2] = glm::dvec4(f, 0.0);
  m[3] = glm::dvec4(l.origin, 1.0);
  return m;
}

}  // namespace

glm::dmat4 miTransform(const MiDocument& doc, const MiElem& transform, MiLookAt* lookAt) {
  glm::dmat4 m(1.0);
  MiLookAt l;
  int steps = 0, lookAts = 0;
  for (const MiElem& e : doc.children(transform)) {
    const std::string t = lower(e.tag());  // Mitsuba 0.x spells it lookAt
    const MiLoc at = doc.loc(e);
    glm::dmat4 step(1.0);
    if (t == "translate") {
      step = glm::translate(glm::dmat4(1.0), stepVector(doc, e, 0.0, false));
    } else if (t == "scale") {
      const glm::dvec3 s = stepVector(doc, e, 1.0, true);
      step = glm::scale(glm::dmat4(1.0), s);
    } else if (t == "rotate") {
      const glm::dvec3 axis = stepVector(doc, e, 0.0, false);
      if (!(glm::length(axis) > 0.0)) mitsubaFail(at, "<rotate>: the axis is zero");
      const std::vector<double> a = miNumbers(at, "<rotate> 'angle'", doc.hasAttr(e, "angle") ? doc.attr(e, "angle") : "");
      if (a.size() != 1) mitsubaFail(at, "<rotate>: 'angle' must be one number (degrees)");
      step = glm::rotate(glm::dmat4(1.0), glm::radians(a[0]), glm::normalize(axis));
    } else if (t == "matrix") {
      const std::vector<double> v = miNumbers(at, "<matrix> 'value'", doc.attr(e, "value"));
      if (v.size() != 16 && v.size() != 9) mitsubaFail(at, "<matrix>: 'value' must have 16 (or 9) numbers, row by row");
      const int n = v.size() == 16 ? 4 : 3;
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) step[c][r] = v[std::size_t(r * n + c)];
      if (n == 4 && (step[0][3] != 0.0 || step[1][3] != 0.0 || step[2][3] != 0.0 || step[3][3] != 1.0))
        mitsubaFail(at, "<matrix>: a projective matrix (last row not 0 0 0 1) is not a placement");
    } else if (t == "lookat") {
      step = lookAtMatrix(doc, e, l);
      ++lookAts;
    } else {
      mitsubaFail(at, "<transform>: unknown step <" + oneLine(e.tag(), 40) + "> (translate, rotate, scale, matrix, lookat)");
    }
    m = step * m;
    ++steps;
  }
  if (lookAt) {
    *lookAt = l;
    lookAt->only = steps == 1 && lookAts == 1;
  }
  return m;
}

}  // namespace montecl
