// light_table.cpp: builds the light-record table and the light kinds' shares of light samples
// (light_table.h), in double, stored as float (the last cdf of each kind exactly 1).
#include "render/light_table.h"

#include <cmath>

#include "kernels/shared/lights.h"

namespace montecl {
namespace {

constexpr double kPi = 3.14159265358979323846;

double lum(const glm::vec3& c) { return double(luminance(float3(c.x, c.y, c.z))); }

// Mean luminance of the environment's radiance over the sphere (texels weighted by their solid
// angle, sin(theta) of their row).
double environmentMeanLuminance(const EnvironmentTable& env) {
  const glm::vec3 e(env.radiance.x, env.radiance.y, env.radiance.z);
  if (env.width == 0 || env.height == 0) return lum(e);
  double sum = 0.0, weight = 0.0;
  for (uint y = 0; y < env.height; ++y) {
    const double s = std::sin(kPi * (double(y) + 0.5) / double(env.height));
    for (uint x = 0; x < env.width; ++x) {
      const float4 t = env.map[std::size_t(y) * env.width + x];
      sum += s * lum(e * glm::vec3(t.x, t.y, t.z));
      weight += s;
    }
  }
  return weight > 0.0 ? sum / weight : 0.0;
}

double lightPower(const LightDesc& l, double sceneRadius) {
  const double li = lum(l.color);
  switch (l.kind) {
    case PunctualKind::Point: return 4.0 * kPi * li;
    case PunctualKind::Spot: {
      const double cb = std::cos(double(l.beamDegrees) * kPi / 180.0);
      const double cc = std::cos(double(l.cutoffDegrees) * kPi / 180.0);
      return 2.0 * kPi * li * (1.0 - 0.5 * (cb + cc));
    }
    case PunctualKind::Directional:
    case PunctualKind::Sun: return kPi * sceneRadius * sceneRadius * li;  // E over the scene's disk
  }
  return 0.0;
}

LightRecord makeRecord(const LightDesc& l) {
  LightRecord r{};
  r.position = float4(l.position.x, l.position.y, l.position.z, 0.0f);
  r.direction = float4(l.direction.x, l.direction.y, l.direction.z, 0.0f);
  r.intensity = float4(l.color.x, l.color.y, l.color.z, 0.0f);
  if (l.kind == PunctualKind::Spot) {
    const float degToRad = float(kPi / 180.0);
    const float cutoff = l.cutoffDegrees * degToRad, beam = l.beamDegrees * degToRad;
    r.cone = float4(std::cos(cutoff), std::cos(beam), cutoff, cutoff > beam ? 1.0f / (cutoff - beam) : 0.0f);
  }
  if (l.kind == PunctualKind::Sun) {  // light_sun.h: radiance E / (pi sin^2 alpha), the cone in double
    const double alpha = 0.5 * double(l.angleDegrees) * kPi / 180.0;
    const double s = std::sin(alpha), oneMinusCos = 2.0 * std::sin(0.5 * alpha) * std::sin(0.5 * alpha);
    const glm::dvec3 radiance = glm::dvec3(l.color) / (kPi * s * s);
    r.intensity = float4(float(radiance.x), float(radiance.y), float(radiance.z), 0.0f);
    r.cone = float4(float(std::cos(alpha)), float(2.0 * kPi * oneMinusCos), float(oneMinusCos), 0.0f);
  }
  return r;
}

}  // namespace

LightTable buildLightTable(const Scene& scene, float emitterPower, const EnvironmentTable& environment, bool lit) {
  LightTable t;
  LightSelection& s = t.selection;
  if (!lit) return t;
  const double radius = std::max(0.5 * double(glm::length(scene.boundsMax - scene.boundsMin)), 1e-6);
  const bool env = environment.radiance.w != 0.0f;
  double kindPower[6] = {env ? 4.0 * kPi * kPi * radius * radius * environmentMeanLuminance(environment) : 0.0,
                         kPi * double(emitterPower), 0.0, 0.0, 0.0, 0.0};
  uint* first[4] = {&s.pointFirst, &s.spotFirst, &s.directionalFirst, &s.sunFirst};
  uint* count[4] = {&s.pointCount, &s.spotCount, &s.directionalCount, &s.sunCount};
  const PunctualKind kinds[4] = {PunctualKind::Point, PunctualKind::Spot, PunctualKind::Directional, PunctualKind::Sun};
  for (int k = 0; k < 4; ++k) {
    *first[k] = uint(t.records.size());
    std::vector<double> power;
    double total = 0.0;
    for (const LightDesc& l : scene.lights) {
      const double p = l.kind == kinds[k] ? lightPower(l, radius) : 0.0;
      if (!(p > 0.0)) continue;  // emits nothing: not a light
      t.records.push_back(makeRecord(l));
      power.push_back(p);
      total += p;
    }
    double running = 0.0;
    for (std::size_t i = 0; i < power.size(); ++i) {
      LightRecord& r = t.records[*first[k] + i];
      running += power[i];
      r.direction.w = float(power[i] / total);
      r.position.w = i + 1 == power.size() ? 1.0f : float(running / total);
    }
    *count[k] = uint(power.size());
    kindPower[2 + k] = total;
  }
  s.lightCount = uint(t.records.size());
  double all = 0.0;
  for (double p : kindPower) all += p;
  if (!(all > 0.0)) {  // nothing emits: an environment (black) keeps every sample, as before
    s.shareEnvironment = env ? 1.0f : 0.0f;
    return t;
  }
  float* share[6] = {&s.shareEnvironment, &s.shareArea, &s.sharePoint, &s.shareSpot, &s.shareDirectional, &s.shareSun};
  for (int k = 0; k < 6; ++k) *share[k] = float(kindPower[k] / all);  // one kind alone: exactly 1
  return t;
}

}  // namespace montecl
