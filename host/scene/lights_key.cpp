// lights_key.cpp: parses and checks the scene file's "lights" list (lights_key.h).
#include "scene/lights_key.h"

#include <cmath>
#include <string>

#include "scene/value_limits.h"

namespace montecl {
namespace {

using nlohmann::json;

glm::vec3 unitDirection(const JsonCtx& ctx, const json& obj, const std::string& prefix) {
  const std::string where = childKey(prefix, "direction");
  const glm::vec3 d = getVec3(ctx, requireKey(ctx, obj, prefix, "direction"), where);
  const float len = glm::length(d);
  if (!(len > 0.0f) || !std::isfinite(len)) jsonFail(ctx, where, "must be a finite, nonzero vector");
  return d / len;
}

// An angle in degrees in (0, 90].
float coneAngle(const JsonCtx& ctx, const json& obj, const std::string& prefix, const char* key, float fallback) {
  const json* v = optionalKey(obj, key);
  if (!v) return fallback;
  const std::string where = childKey(prefix, key);
  const float a = getFloat(ctx, *v, where);
  if (!(a > 0.0f && a <= 90.0f)) jsonFail(ctx, where, "must be an angle in degrees in (0, 90]");
  return a;
}

LightDesc parseLight(const JsonCtx& ctx, const json& obj, const std::string& prefix) {
  requireObject(ctx, obj, prefix);
  const std::string typeKey = childKey(prefix, "type");
  const std::string type = getString(ctx, requireKey(ctx, obj, prefix, "type"), typeKey, "a light type");
  LightDesc l;
  if (type == "point" || type == "spot") {
    l.kind = type == "point" ? PunctualKind::Point : PunctualKind::Spot;
    l.position = getVec3(ctx, requireKey(ctx, obj, prefix, "position"), childKey(prefix, "position"));
    l.color = getColor(ctx, requireKey(ctx, obj, prefix, "intensity"), childKey(prefix, "intensity"));
  } else if (type == "directional" || type == "sun") {
    l.kind = type == "sun" ? PunctualKind::Sun : PunctualKind::Directional;
    l.color = getColor(ctx, requireKey(ctx, obj, prefix, "irradiance"), childKey(prefix, "irradiance"));
  } else {
    jsonFail(ctx, typeKey,
             "unknown light type \"" + type + "\" (expected \"point\", \"spot\", \"directional\" or \"sun\")");
  }
  if (l.kind == PunctualKind::Sun) {
    if (const json* v = optionalKey(obj, "angle")) {
      l.angleDegrees = getFloat(ctx, *v, childKey(prefix, "angle"));
      if (!(l.angleDegrees > 0.0f && l.angleDegrees < 180.0f))
        jsonFail(ctx, childKey(prefix, "angle"), "must be an angular diameter in degrees in (0, 180)");
    }
  }
  if (l.kind != PunctualKind::Point) l.direction = unitDirection(ctx, obj, prefix);
  if (l.kind == PunctualKind::Spot) {
    l.cutoffDegrees = coneAngle(ctx, obj, prefix, "cutoff_angle", 20.0f);
    l.beamDegrees = coneAngle(ctx, obj, prefix, "beam_width", l.cutoffDegrees * 0.75f);  // Mitsuba 3's default
    if (l.beamDegrees > l.cutoffDegrees)
      jsonFail(ctx, childKey(prefix, "beam_width"), "must not exceed cutoff_angle");
  }
  const std::string colourKey = l.kind == PunctualKind::Point || l.kind == PunctualKind::Spot ? "intensity" : "irradiance";
  if (const ValueProblem v = lightValueProblem(l.kind, glm::dvec3(l.color), l.angleDegrees, colourKey))
    jsonFail(ctx, childKey(prefix, v.key), v.what);
  switch (l.kind) {
    case PunctualKind::Point: warnUnknownKeys(ctx, obj, prefix, {"type", "position", "intensity"}); break;
    case PunctualKind::Spot:
      warnUnknownKeys(ctx, obj, prefix, {"type", "position", "direction", "intensity", "cutoff_angle", "beam_width"});
      break;
    case PunctualKind::Directional: warnUnknownKeys(ctx, obj, prefix, {"type", "direction", "irradiance"}); break;
    case PunctualKind::Sun: warnUnknownKeys(ctx, obj, prefix, {"type", "direction", "irradiance", "angle"}); break;
  }
  return l;
}

}  // namespace

std::vector<LightDesc> parseLightsKey(const JsonCtx& ctx, const json& value) {
  if (!value.is_array()) jsonFail(ctx, "lights", std::string("expected a list of lights, got ") + value.type_name());
  std::vector<LightDesc> lights;
  for (std::size_t i = 0; i < value.size(); ++i)
    lights.push_back(parseLight(ctx, value[i], "lights[" + std::to_string(i) + "]"));
  return lights;
}

}  // namespace montecl
