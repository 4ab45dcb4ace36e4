// mitsuba_emitters.cpp: Mitsuba emitters as montecl's lights (mitsuba_emitters.h).
#include "scene/mitsuba_emitters.h"

#include <algorithm>
#include <cmath>

#include "scene/load_util.h"

namespace montecl {
namespace {

glm::vec3 emission(MiContext& c, const MiProps& p, const char* name) {
  glm::vec3 v(1.0f);
  if (!miColourInto(c, p, name, &v, nullptr, nullptr)) mitsubaFail(p.loc, p.type + ": '" + name + "' is required");
  const float scale = float(p.getFloat("scale", 1.0));
  v *= scale;
  if (!(v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f && std::isfinite(v.x + v.y + v.z)))
    mitsubaFail(p.locOf(name), p.type + ": '" + std::string(name) + "' x scale must be finite and >= 0");
  return v;
}

glm::vec3 unit(const MiProps& p, const glm::dvec3& d, const char* what) {
  if (!(glm::length(d) > 0.0)) mitsubaFail(p.loc, p.type + ": the " + std::string(what) + " is zero");
  return glm::vec3(glm::normalize(d));
}

void environment(MiContext& c, const MiProps& p) {
  EnvironmentDesc& env = c.scene.environment;
  if (env.enabled) {
    c.warn(p.loc, "emitter \"" + p.type + "\": montecl has one environment light; this second one is left out");
    return;
  }
  env.enabled = true;
  if (p.type == "constant") {
    env.radiance = emission(c, p, "radiance");
    return;
  }
  const std::string name = p.getString("filename", "");
  if (name.empty()) mitsubaFail(p.loc, "envmap: 'filename' is required");
  env.file = c.doc.resolve(name);
  const std::string problem = fileProblem(env.file);
  if (!problem.empty()) mitsubaFail(p.locOf("filename"), "envmap: cannot open '" + oneLine(name, 100) + "': " + problem);
  c.scene.inputFiles.push_back(env.file);
  env.scale = float(p.getFloat("scale", 1.0));
  if (!(env.scale >= 0.0f && std::isfinite(env.scale))) mitsubaFail(p.locOf("scale"), "envmap: 'scale' must be finite and >= 0");
  // montecl's latitude-longitude lookup is Mitsuba's (u from atan2(x, -z), v from acos(y)); of a
  // to_world it takes a rotation about +y.
  const glm::dmat3 m(p.getTransform("to_world"));
  const double angle = std::atan2(-m[0][2], m[0][0]);
  const glm::dmat3 rotY(glm::dvec3(std::cos(angle), 0.0, -std::sin(angle)), glm::dvec3(0.0, 1.0, 0.0),
                        glm::dvec3(std::sin(angle), 0.0, std::cos(angle)));
  double off = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) off = std::max(off, std::fabs(m[i][j] - rotY[i][j]));
  if (off > 1e-6) c.warn(p.locOf("to_world"), "envmap: montecl rotates environment maps about +y only; the rest of to_world is left out");
  env.rotateYDegrees = float(glm::degrees(angle));
}

}  // namespace

MiAreaLight miAreaEmitter(MiContext& c, const MiElem& e) {
  const MiProps p(c.doc, e);
  if (p.type != "area") mitsubaFail(p.loc, "a shape's <emitter> must be of type \"area\", got \"" + oneLine(p.type, 40) + "\"");
  MiAreaLight a;
  if (!miColourInto(c, p, "radiance", &a.radiance, &a.texture, &a.sampling)) mitsubaFail(p.loc, "area: 'radiance' is required");
  if (!(a.radiance.x >= 0.0f && a.radiance.y >= 0.0f && a.radiance.z >= 0.0f && std::isfinite(a.radiance.x + a.radiance.y + a.radiance.z)))
    mitsubaFail(p.locOf("radiance"), "area: 'radiance' must be finite and >= 0");
  p.reportUnused("emitter \"area\"", c.warnings);
  return a;
}

void miEmitter(MiContext& c, const MiElem& e) {
  const MiProps p(c.doc, e);
  const std::string what = "emitter \"" + oneLine(p.type, 40) + "\"";
  LightDesc l;
  const glm::dmat4 m = p.getTransform("to_world");
  if (p.type == "constant" || p.type == "envmap") {
    environment(c, p);
    p.reportUnused(what, c.warnings);
    return;
  }
  if (p.type == "point") {
    l.kind = PunctualKind::Point;
    const std::optional<glm::dvec3> at = p.getPoint("position");
    l.position = glm::vec3(at ? *at : glm::dvec3(m[3]));
    l.color = emission(c, p, "intensity");
  } else if (p.type == "spot") {
    l.kind = PunctualKind::Spot;
    l.position = glm::vec3(glm::dvec3(m[3]));
    l.direction = unit(p, glm::dvec3(m[2]), "direction (to_world's +z)");
    l.color = emission(c, p, "intensity");
    l.cutoffDegrees = float(p.getFloat("cutoff_angle", 20.0));
    l.beamDegrees = float(p.getFloat("beam_width", double(l.cutoffDegrees) * 0.75));
    if (!(l.cutoffDegrees > 0.0f && l.cutoffDegrees <= 90.0f)) mitsubaFail(p.locOf("cutoff_angle"), "spot: 'cutoff_angle' must be in (0, 90]");
    if (!(l.beamDegrees > 0.0f && l.beamDegrees <= l.cutoffDegrees))
      mitsubaFail(p.locOf("beam_width"), "spot: 'beam_width' must be in (0, cutoff_angle]");
    if (p.find("texture")) c.warn(p.locOf("texture"), "spot: a projected texture is not read by montecl, left out");
  } else if (p.type == "directional") {
    l.kind = PunctualKind::Directional;
    const std::optional<glm::dvec3> d = p.getPoint("direction");
    l.direction = unit(p, d ? *d : glm::dvec3(m[2]), "direction");
    l.color = emission(c, p, "irradiance");
  } else if (p.type == "area") {
    mitsubaFail(p.loc, "an \"area\" emitter belongs inside a <shape>");
  } else {
    c.warn(p.loc, what + " not read by montecl (it reads area, constant, envmap, point, spot, directional), left out");
    return;
  }
  p.reportUnused(what, c.warnings);
  c.scene.lights.push_back(l);
}

}  // namespace montecl
