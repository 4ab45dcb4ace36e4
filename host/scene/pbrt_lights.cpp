// pbrt_lights.cpp: pbrt-v4 light sources as montecl lights (pbrt_lights.h): reads LightSource
// parameters, writes Scene::lights / Scene::environment. pbrt-v4 normalises an RGB emission to its
// illuminant so that "rgb L" [r g b] is radiance (r, g, b) in linear sRGB, as montecl reads it.
#include "scene/pbrt_lights.h"

#include <algorithm>
#include <cmath>

#include "scene/load_util.h"
#include "scene/value_limits.h"

namespace montecl {
namespace {

glm::vec3 point(const PbrtParams& p, const std::string& name, glm::vec3 fallback) {
  const std::vector<double> v = p.getNumbers(name, {"point3", "point"}, 3);
  if (v.empty()) return fallback;
  if (v.size() != 3) pbrtFail(p.find(name)->loc, "'" + name + "' must be one point");
  return glm::vec3(float(v[0]), float(v[1]), float(v[2]));
}

glm::vec3 placePoint(const glm::dmat4& m, glm::vec3 p) { return glm::vec3(m * glm::dvec4(glm::dvec3(p), 1.0)); }

glm::vec3 placeDirection(const PbrtParams& p, const glm::dmat4& m, glm::vec3 d) {
  const glm::dvec3 w = glm::dmat3(m) * glm::dvec3(d);
  if (!(glm::length(w) > 0.0)) pbrtFail(p.loc, "'from' and 'to' must differ (the light has no direction)");
  return glm::vec3(glm::normalize(w));
}

glm::vec3 lightEmission(const PbrtParams& p, const std::string& name, std::vector<std::string>& warnings) {
  glm::vec3 c(1.0f);
  pbrtLightSpectrum(p, name, c, warnings);
  const double scale = p.getFloat("scale", 1.0);
  const glm::dvec3 scaled = glm::dvec3(c) * scale;  // in double: the product may pass float range
  if (!(scaled.x >= 0.0 && scaled.y >= 0.0 && scaled.z >= 0.0 && std::isfinite(scaled.x + scaled.y + scaled.z)))
    pbrtFail(p.loc, "the light's '" + name + "' x scale must be finite and >= 0");
  if (const ValueProblem v = lightValueProblem(PunctualKind::Point, scaled, 0.0, name))
    pbrtFail(p.loc, "the light's '" + name + "' x scale: " + v.what);
  return glm::vec3(scaled);
}

}  // namespace

void pbrtLightSource(const std::string& type, const PbrtParams& p, const glm::dmat4& m,
                     const std::string& baseFile, Scene& scene, std::vector<std::string>& warnings) {
  const std::string at = p.loc.str() + ": LightSource \"" + oneLine(type, 40) + "\": ";
  LightDesc l;
  if (type == "point") {
    l.kind = PunctualKind::Point;
    l.position = placePoint(m, point(p, "from", glm::vec3(0.0f)));
    l.color = lightEmission(p, "I", warnings);
  } else if (type == "spot") {
    l.kind = PunctualKind::Spot;
    const glm::vec3 from = point(p, "from", glm::vec3(0.0f)), to = point(p, "to", glm::vec3(0, 0, 1));
    l.position = placePoint(m, from);
    l.direction = placeDirection(p, m, to - from);
    l.color = lightEmission(p, "I", warnings);
    // pbrt: full intensity within coneangle - conedelta, a smoothstep falloff to zero at coneangle.
    // montecl's spot: cutoff_angle and beam_width with its own falloff between them.
    double cone = p.getFloat("coneangle", 30.0), delta = p.getFloat("conedelta", 5.0);
    if (!(cone > 0.0)) pbrtFail(p.loc, "spot: 'coneangle' must be > 0");
    if (cone > 90.0) {
      warnings.push_back(at + "coneangle " + std::to_string(cone) + " above montecl's 90 degrees, clamped");
      cone = 90.0;
    }
    l.cutoffDegrees = float(cone);
    l.beamDegrees = float(std::max(cone - std::max(delta, 0.0), 1e-3));
    warnings.push_back(at + "montecl's spot falloff between beam_width and cutoff_angle is not pbrt's smoothstep; the edge differs slightly");
  } else if (type == "distant") {
    l.kind = PunctualKind::Directional;
    const glm::vec3 from = point(p, "from", glm::vec3(0.0f)), to = point(p, "to", glm::vec3(0, 0, 1));
    l.direction = placeDirection(p, m, to - from);
    l.color = lightEmission(p, "L", warnings);
  } else if (type == "infinite") {
    if (scene.environment.enabled) {
      warnings.push_back(at + "montecl has one environment light; this second one is left out");
      for (const PbrtParam& q : p.list) q.used = true;
      return;
    }
    EnvironmentDesc& env = scene.environment;
    env.enabled = true;
    const std::string file = p.getString("filename", "");
    glm::vec3 L(1.0f);
    const bool hasL = pbrtLightSpectrum(p, "L", L, warnings);
    if (!file.empty() && hasL) pbrtFail(p.loc, "infinite: give either 'L' or 'filename', not both");
    env.radiance = L;
    env.scale = float(p.getFloat("scale", 1.0));
    if (!(env.scale >= 0.0f && std::isfinite(env.scale))) pbrtFail(p.loc, "infinite: 'scale' must be finite and >= 0");
    if (!file.empty()) {
      env.file = besideFile(baseFile, file);
      const std::string problem = fileProblem(env.file);
      if (!problem.empty()) pbrtFail(p.find("filename")->loc, "infinite: cannot open '" + oneLine(file, 100) + "': " + problem);
      scene.inputFiles.push_back(env.file);
      // pbrt-v4's map is equal-area octahedral, looked up in light space: resampled when the
      // environment is built, through the light's transform and the world's mirror alike.
      env.equalArea = true;
      env.mapFromWorld = glm::inverse(glm::dmat3(m));
    }
    return;
  } else {
    warnings.push_back(at + "light type not read by montecl (it reads point, spot, distant, infinite), left out");
    for (const PbrtParam& q : p.list) q.used = true;
    return;
  }
  scene.lights.push_back(l);
}

}  // namespace montecl
