// frame_params.cpp: camera basis (pinhole or thin lens) and render settings packed for the kernels.
#include "render/frame_params.h"

#include "scene/scene_instances.h"

#include <algorithm>
#include <cmath>

#include "scene/camera_basis.h"

namespace montecl {

FrameParams makeFrameParams(const Camera& camera, const RenderSettings& settings, const FrameExtras& extras) {
  const CameraBasis b = cameraBasis(camera);  // validated at scene load (cameraBasisProblem)
  FrameParams f{};
  f.camOrigin = glm::vec4(camera.position, 0.0f);
  f.camTopLeft = glm::vec4(b.topLeft, 0.0f);
  f.camDx = glm::vec4(b.dx, 0.0f);
  f.camDy = glm::vec4(b.dy, 0.0f);
  f.background = glm::vec4(settings.background, 0.0f);
  f.offsetScale = extras.offsetScale;
  f.width = uint(camera.width);
  f.height = uint(camera.height);
  f.seed = settings.seed;
  f.aoSampling = settings.aoSampling == AoSampling::Uniform ? MCL_AO_UNIFORM : MCL_AO_COSINE;
  f.aoDistance = settings.aoDistance;
  f.shadowSlots = extras.shadowSlots;
  f.activeCount = f.width * f.height;
  f.lightSamples = uint(settings.lightSamples);
  f.directSampling = settings.directSampling == DirectSampling::Light  ? MCL_DIRECT_LIGHT
                     : settings.directSampling == DirectSampling::Brdf ? MCL_DIRECT_BRDF
                                                                       : MCL_DIRECT_MIS;
  f.maxDepth = settings.maxDepth;
  f.rrDepth = uint(settings.rrDepth);
  f.lensRadius = camera.apertureRadius;
  f.filterKind = filterKernelKind(settings.filter);
  f.filterRadius = settings.filter.radius;
  if (f.filterKind == MCL_FILTER_TABLE) {
    const std::array<float, MCL_FILTER_BINS> cdf = filterCdf(settings.filter);
    std::copy(cdf.begin(), cdf.end(), f.filterCdf);
  }
  f.focusDistance = camera.focusDistance > 0.0f ? camera.focusDistance : glm::length(camera.target - camera.position);
  f.emitterCount = extras.emitterCount;
  f.emitterPower = extras.emitterPower;
  f.emissionTextured = extras.emissionTextured ? 1u : 0u;
  f.environment = extras.environment;
  f.envWidth = extras.envWidth;
  f.envHeight = extras.envHeight;
  f.envRotateY = extras.envRotateY;
  f.textureCount = extras.textureCount;
  f.alphaTested = extras.alphaTested ? 1u : 0u;
  f.packetAllRays = extras.packetAllRays ? 1u : 0u;
  f.instanceCount = extras.instanceCount;
  f.recordAovs = extras.recordAovs ? 1u : 0u;
  f.countLanes = extras.countLanes ? 1u : 0u;
  const LightSelection& l = extras.lights;
  f.shareEnvironment = l.shareEnvironment;
  f.shareArea = l.shareArea;
  f.sharePoint = l.sharePoint;
  f.shareSpot = l.shareSpot;
  f.shareDirectional = l.shareDirectional;
  f.shareSun = l.shareSun;
  f.lightCount = l.lightCount;
  f.pointFirst = l.pointFirst;
  f.pointCount = l.pointCount;
  f.spotFirst = l.spotFirst;
  f.spotCount = l.spotCount;
  f.directionalFirst = l.directionalFirst;
  f.directionalCount = l.directionalCount;
  f.sunFirst = l.sunFirst;
  f.sunCount = l.sunCount;
  f.sampler = settings.sampler == Sampler::Sobol ? MCL_SAMPLER_SOBOL : MCL_SAMPLER_INDEPENDENT;
  f.sobolSplits = std::uint32_t(sobolSplitsUsed(settings));
  return f;
}

namespace {
// maxAbs grown to v's largest |coordinate|.
void growMaxAbs(float& maxAbs, const glm::vec3& v) { maxAbs = std::max({maxAbs, std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

float offsetScaleOfMaxAbs(float maxAbs) {
  if (!(maxAbs > 0.0f) || maxAbs >= 1.0f) return 1.0f;
  int e = 0;
  const float m = std::frexp(maxAbs, &e);  // maxAbs = m * 2^e, m in [0.5, 1)
  return std::ldexp(1.0f, m == 0.5f ? e - 1 : e);
}
}  // namespace

float offsetScaleFor(const std::vector<SceneTriangle>& triangles) {
  float maxAbs = 0.0f;
  for (const SceneTriangle& t : triangles)
    for (const glm::vec3& v : t.v) growMaxAbs(maxAbs, v);
  return offsetScaleOfMaxAbs(maxAbs);
}

// With instances: the world-space triangles and the instances' placed boxes (object-space
// triangles say nothing about where they end up).
float offsetScaleForScene(const Scene& scene) {
  if (scene.instances.empty() && scene.meshRanges.empty()) return offsetScaleFor(scene.triangles);
  const std::vector<std::uint8_t> instanced = instancedTriangles(scene);
  float maxAbs = 0.0f;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i)
    if (!instanced[i])
      for (const glm::vec3& v : scene.triangles[i].v) growMaxAbs(maxAbs, v);
  for (const glm::vec3& v : instanceBoxCorners(scene)) growMaxAbs(maxAbs, v);
  return offsetScaleOfMaxAbs(maxAbs);
}

bool packetTraversalForAllRays(std::size_t wideNodes) {
  return wideNodes <= 16;
}

}  // namespace montecl
