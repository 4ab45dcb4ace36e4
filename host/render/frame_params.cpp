// frame_params.cpp: pinhole camera basis and render settings packed for the kernels.
#include "render/frame_params.h"

#include <cmath>

namespace montecl {

FrameParams makeFrameParams(const Camera& camera, const RenderSettings& settings, uint shadowSlots) {
  glm::vec3 forward = glm::normalize(camera.target - camera.position);
  glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  glm::vec3 up = glm::cross(right, forward);
  float tanHalf = std::tan(glm::radians(camera.fovY) * 0.5f);
  float aspect = float(camera.width) / float(camera.height);
  glm::vec3 topLeft = forward - right * (tanHalf * aspect) + up * tanHalf;
  glm::vec3 dx = right * (2.0f * tanHalf * aspect / float(camera.width));
  glm::vec3 dy = -up * (2.0f * tanHalf / float(camera.height));

  FrameParams f{};
  f.camOrigin = glm::vec4(camera.position, 0.0f);
  f.camTopLeft = glm::vec4(topLeft, 0.0f);
  f.camDx = glm::vec4(dx, 0.0f);
  f.camDy = glm::vec4(dy, 0.0f);
  f.background = glm::vec4(settings.background, 0.0f);
  f.width = uint(camera.width);
  f.height = uint(camera.height);
  f.seed = settings.seed;
  f.aoSampling = settings.aoSampling == AoSampling::Uniform ? MCL_AO_UNIFORM : MCL_AO_COSINE;
  f.aoDistance = settings.aoDistance;
  f.shadowSlots = shadowSlots;
  f.activeCount = f.width * f.height;
  f.lightSamples = uint(settings.lightSamples);
  f.directSampling = settings.directSampling == DirectSampling::Light  ? MCL_DIRECT_LIGHT
                     : settings.directSampling == DirectSampling::Brdf ? MCL_DIRECT_BRDF
                                                                       : MCL_DIRECT_MIS;
  return f;
}

}  // namespace montecl
