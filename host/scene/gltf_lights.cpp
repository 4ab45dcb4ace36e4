// gltf_lights.cpp: KHR_lights_punctual lights onto scene.lights (see gltf_lights.h).
#include "scene/gltf_lights.h"

#include <cmath>

#include "scene/value_limits.h"

namespace montecl {

int gltfNodeLight(const tinygltf::Node& node) {
  const auto it = node.extensions.find("KHR_lights_punctual");
  if (it == node.extensions.end() || !it->second.IsObject() || !it->second.Has("light")) return -1;
  const tinygltf::Value& v = it->second.Get("light");
  return v.IsNumber() || v.IsInt() ? v.GetNumberAsInt() : -2;  // -2: present but not an index
}

namespace {

bool isNumber(const tinygltf::Value& v) { return v.IsNumber() || v.IsInt(); }

// tinygltf reads a light's values only when they have the right JSON type and leaves the default
// otherwise ("intensity": "x" rendered at intensity 1): the types are checked on the raw object.
void checkLightTypes(const std::string& file, const tinygltf::Model& m, std::size_t index, const std::string& where) {
  const auto ext = m.extensions.find("KHR_lights_punctual");
  if (ext == m.extensions.end() || !ext->second.IsObject() || !ext->second.Has("lights")) return;
  const tinygltf::Value& lights = ext->second.Get("lights");
  if (!lights.IsArray() || index >= lights.ArrayLen()) return;
  const tinygltf::Value& l = lights.Get(int(index));
  if (!l.IsObject()) loadFail(file, where, "must be an object");
  for (const char* key : {"intensity", "range"})
    if (l.Has(key) && !isNumber(l.Get(key))) loadFail(file, where + "." + key, "must be a number");
  if (l.Has("type") && !l.Get("type").IsString()) loadFail(file, where + ".type", "must be a string");
  if (l.Has("color")) {
    const tinygltf::Value& c = l.Get("color");
    if (!c.IsArray() || c.ArrayLen() != 3 || !isNumber(c.Get(0)) || !isNumber(c.Get(1)) || !isNumber(c.Get(2)))
      loadFail(file, where + ".color", "must be an array of 3 numbers");
  }
  if (l.Has("spot")) {
    const tinygltf::Value& s = l.Get("spot");
    if (!s.IsObject()) loadFail(file, where + ".spot", "must be an object");
    for (const char* key : {"innerConeAngle", "outerConeAngle"})
      if (s.Has(key) && !isNumber(s.Get(key))) loadFail(file, where + ".spot." + key, "must be a number");
  }
}

}  // namespace

void addGltfLight(const std::string& file, const tinygltf::Model& m, int index, const glm::dmat4& world, Scene& scene,
                  KindWarnings& unused) {
  const std::string where = "KHR_lights_punctual.lights[" + std::to_string(index) + "]";
  if (index < 0 || static_cast<std::size_t>(index) >= m.lights.size())
    loadFail(file, "KHR_lights_punctual.light", "light index " + std::to_string(index) + " out of range");
  checkLightTypes(file, m, static_cast<std::size_t>(index), where);
  const tinygltf::Light& g = m.lights[static_cast<std::size_t>(index)];
  LightDesc l;
  if (g.type == "point") l.kind = PunctualKind::Point;
  else if (g.type == "spot") l.kind = PunctualKind::Spot;
  else if (g.type == "directional") l.kind = PunctualKind::Directional;
  else loadFail(file, where + ".type", "unknown light type '" + oneLine(g.type, 40) + "' (point, spot, directional)");
  glm::dvec3 colour(1.0);
  if (!g.color.empty()) {
    if (g.color.size() != 3) loadFail(file, where + ".color", "expected 3 numbers");
    colour = glm::dvec3(g.color[0], g.color[1], g.color[2]);
  }
  for (int c = 0; c < 3; ++c)
    if (!(std::isfinite(colour[c]) && colour[c] >= 0.0)) loadFail(file, where + ".color", "components must be finite and >= 0");
  if (!(std::isfinite(g.intensity) && g.intensity >= 0.0)) loadFail(file, where + ".intensity", "must be finite and >= 0");
  // In double: colour x intensity past float range was an infinite light, a black image.
  if (const ValueProblem v = lightValueProblem(l.kind, colour * g.intensity, 0.0, "intensity"))
    loadFail(file, where + "." + v.key, "colour x intensity " + v.what);
  l.color = glm::vec3(colour * g.intensity);
  l.position = glm::vec3(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  const glm::dvec3 axis = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
  if (!(glm::length(axis) > 0.0) || !std::isfinite(glm::length(axis)))
    loadFail(file, where, "its node's transform leaves it no direction");
  l.direction = glm::vec3(glm::normalize(axis));
  if (l.kind == PunctualKind::Spot) {
    const double inner = g.spot.innerConeAngle, outer = g.spot.outerConeAngle;
    if (!(outer > 0.0 && outer <= M_PI / 2 + 1e-9)) loadFail(file, where + ".spot.outerConeAngle", "must be in (0, pi/2]");
    if (!(inner >= 0.0 && inner < outer)) loadFail(file, where + ".spot.innerConeAngle", "must be in [0, outerConeAngle)");
    l.cutoffDegrees = float(outer * 180.0 / M_PI);
    l.beamDegrees = float(inner * 180.0 / M_PI);
  }
  if (g.range > 0.0)
    unused.add("light range", where + ".range", "range not used by montecl (lights fall off as 1/d^2 without a cut-off)");
  scene.lights.push_back(l);
}

}  // namespace montecl
