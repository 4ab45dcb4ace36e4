// scene_digest.cpp: the scene content hash and the integrator settings string of a render's provenance.
#include "scene/scene_digest.h"

#include <cstring>

#include "util/hash.h"

namespace montecl {
namespace {

void append(Fnv1a64& bytes, const void* data, std::size_t size) { bytes.add(data, size); }

void appendVec(Fnv1a64& bytes, const glm::vec3& v) {
  const float f[3] = {v.x, v.y, v.z};
  append(bytes, f, sizeof f);
}

}  // namespace

std::string sceneDigest(const Scene& scene) {
  Fnv1a64 bytes;  // hashed as they come (not gathered into a string of the whole scene first)
  for (const SceneTriangle& t : scene.triangles) {
    for (const glm::vec3& v : t.v) appendVec(bytes, v);
    append(bytes, &t.material, sizeof t.material);
    append(bytes, &t.attributes, sizeof t.attributes);
    if (t.attributes & kHasNormals)
      for (const glm::vec3& n : t.n) appendVec(bytes, n);
    if (t.attributes & kHasUv)
      for (const glm::vec2& uv : t.uv) append(bytes, &uv, sizeof uv);
  }
  bytes.add("materials");
  for (const MaterialDesc& m : scene.materials) {
    appendVec(bytes, m.albedo);
    appendVec(bytes, m.emission);
    appendVec(bytes, m.specular);
    append(bytes, &m.specularExponent, sizeof m.specularExponent);
    append(bytes, &m.alphaCutoff, sizeof m.alphaCutoff);
    bytes.add(m.albedoTexture + '\0' + m.alphaTexture + '\0' + (m.twoSidedEmission ? '2' : '1'));
    // The kind only when it is not the first (diffuse): every scene from before kinds existed keeps
    // its digest, so its checkpoints still resume.
    if (m.kind != MCL_MATERIAL_diffuse) bytes.add("kind" + std::to_string(m.kind));
  }
  if (scene.environment.enabled) {  // the map by its path (its pixels are not hashed)
    const EnvironmentDesc& e = scene.environment;
    bytes.add("environment" + e.file);
    appendVec(bytes, e.radiance);
    append(bytes, &e.scale, sizeof e.scale);
    append(bytes, &e.rotateYDegrees, sizeof e.rotateYDegrees);
  }
  bytes.add("camera");
  appendVec(bytes, scene.camera.position);
  appendVec(bytes, scene.camera.target);
  appendVec(bytes, scene.camera.up);
  append(bytes, &scene.camera.fovY, sizeof scene.camera.fovY);
  if (scene.camera.apertureRadius > 0.0f) {  // (pinhole scenes keep their digests)
    append(bytes, &scene.camera.apertureRadius, sizeof scene.camera.apertureRadius);
    append(bytes, &scene.camera.focusDistance, sizeof scene.camera.focusDistance);
  }
  return hex64(bytes.value());
}

}  // namespace montecl
