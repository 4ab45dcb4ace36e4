// scene_digest.cpp: the scene content hash and the integrator settings string of a render's provenance.
#include "scene/scene_digest.h"

#include <cstring>
#include <fstream>
#include <map>

#include "util/hash.h"

namespace montecl {
namespace {

void append(Fnv1a64& bytes, const void* data, std::size_t size) { bytes.add(data, size); }

void appendVec(Fnv1a64& bytes, const glm::vec3& v) {
  const float f[3] = {v.x, v.y, v.z};
  append(bytes, f, sizeof f);
}

// A file's bytes as a hash, read in chunks: a texture or environment map counts by its content,
// not its name (another file under the same name is another scene; a copied folder is the same).
// "" stands for no file; a file that cannot be read hashes as such (loading it fails later anyway).
std::uint64_t fileContentHash(const std::string& path, std::map<std::string, std::uint64_t>& cache) {
  if (path.empty()) return 0;
  const auto it = cache.find(path);
  if (it != cache.end()) return it->second;
  Fnv1a64 h;
  std::ifstream in(path, std::ios::binary);
  char chunk[1 << 16];
  while (in && (in.read(chunk, sizeof chunk) || in.gcount() > 0)) h.add(chunk, std::size_t(in.gcount()));
  if (!in.eof()) h.add("unreadable");
  return cache[path] = h.value();
}

}  // namespace

std::string sceneDigest(const Scene& scene) {
  Fnv1a64 bytes;  // hashed as they come (not gathered into a string of the whole scene first)
  std::map<std::string, std::uint64_t> files;  // content hashes by path (a texture shared by materials is read once)
  for (const auto& [name, encoded] : scene.embeddedImages) {  // held in memory: hashed as held
    Fnv1a64 h;
    h.add(encoded.data(), encoded.size());
    files[name] = h.value();
  }
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    const SceneTriangle& t = scene.triangles[i];
    for (const glm::vec3& v : t.v) appendVec(bytes, v);
    if ((t.attributes & kHasColor) && 3 * i + 2 < scene.vertexColors.size())
      for (std::size_t k = 0; k < 3; ++k) appendVec(bytes, scene.vertexColors[3 * i + k]);
    if ((t.attributes & kHasTangents) && 3 * i + 2 < scene.vertexTangents.size())  // only then: other digests stay
      append(bytes, &scene.vertexTangents[3 * i], 3 * sizeof(glm::vec4));
    append(bytes, &t.material, sizeof t.material);
    append(bytes, &t.attributes, sizeof t.attributes);
    if (t.attributes & kHasNormals)
      for (const glm::vec3& n : t.n) appendVec(bytes, n);
    if (t.attributes & kHasUv)
      for (const glm::vec2& uv : t.uv) append(bytes, &uv, sizeof uv);
  }
  if (!scene.meshRanges.empty() || !scene.instances.empty()) {  // only then: other scenes' digests stay
    bytes.add("instances");
    for (const MeshRange& r : scene.meshRanges) append(bytes, &r, sizeof r);
    for (const SceneInstance& in : scene.instances) {
      append(bytes, &in.range, sizeof in.range);
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) append(bytes, &in.objectToWorld[c][r], sizeof(double));
    }
  }
  bytes.add("materials");
  for (const MaterialDesc& m : scene.materials) {
    appendVec(bytes, m.albedo);
    appendVec(bytes, m.emission);
    appendVec(bytes, m.specular);
    append(bytes, &m.specularExponent, sizeof m.specularExponent);
    append(bytes, &m.alphaCutoff, sizeof m.alphaCutoff);
    const std::uint64_t textures[2] = {fileContentHash(m.albedoTexture, files), fileContentHash(m.alphaTexture, files)};
    append(bytes, textures, sizeof textures);
    bytes.add(m.twoSidedEmission ? "2" : "1");
    if (m.alphaBlend) {  // only when set: the digests of other scenes stay
      bytes.add("alpha_blend");
      append(bytes, &m.alphaFactor, sizeof m.alphaFactor);
    }
    if (!m.emissionTexture.empty()) {  // only when there is one: the digests of other scenes stay
      bytes.add("emission_texture");
      const std::uint64_t e = fileContentHash(m.emissionTexture, files);
      append(bytes, &e, sizeof e);
    }
    if (!m.normalTexture.empty()) {  // only when there is one, as the emission texture's
      bytes.add("normal_texture");
      const std::uint64_t n = fileContentHash(m.normalTexture, files);
      append(bytes, &n, sizeof n);
      append(bytes, &m.normalScale, sizeof m.normalScale);
    }
    if (!m.bumpTexture.empty()) {  // only when there is one, as the emission texture's
      bytes.add("bump_texture");
      const std::uint64_t b = fileContentHash(m.bumpTexture, files);
      append(bytes, &b, sizeof b);
      append(bytes, &m.bumpScale, sizeof m.bumpScale);
    }
    // How the textures are read, only where it is not as they always were (other digests stay).
    for (const TextureSampling* t : {&m.albedoSampling, &m.alphaSampling, &m.emissionSampling,
                                     &m.metallicRoughnessSampling, &m.normalSampling, &m.bumpSampling,
                                     &m.transmissionSampling})
      if (!t->identity()) {
        bytes.add("sampling");
        appendVec(bytes, t->row0);
        appendVec(bytes, t->row1);
        const std::uint32_t w[2] = {t->wrapS, t->wrapT};
        append(bytes, w, sizeof w);
      }
    // The kind only when it is not the first (diffuse): every scene from before kinds existed keeps
    // its digest, so its checkpoints still resume.
    if (m.kind != MCL_MATERIAL_diffuse) {  // and its parameters (diffuse reads none of them)
      bytes.add("kind" + std::to_string(m.kind));
      appendVec(bytes, m.eta);
      appendVec(bytes, m.k);
      const float p[4] = {m.ior, m.kindAlpha, m.metallic, m.roughness};
      append(bytes, p, sizeof p);
      if (!m.metallicRoughnessTexture.empty()) {
        const std::uint64_t mr = fileContentHash(m.metallicRoughnessTexture, files);
        append(bytes, &mr, sizeof mr);
        if (m.specGlossMap) {  // converted per texel with these factors (only then: other digests stay)
          bytes.add("spec-gloss");
          append(bytes, &m.specGloss, sizeof m.specGloss);
          appendVec(bytes, m.specGlossDiffuse);
        }
      }
      if (m.transmission > 0.0f) {  // only when there is some, so other scenes keep their digests
        bytes.add(m.transmissionSolid ? "transmission solid" : "transmission thin");
        append(bytes, &m.transmission, sizeof m.transmission);
        if (!m.transmissionTexture.empty()) {
          const std::uint64_t tt = fileContentHash(m.transmissionTexture, files);
          append(bytes, &tt, sizeof tt);
        }
      }
      if (m.transmissionTinted) bytes.add("transmission tinted");  // only then, likewise
      if (m.kind == MCL_MATERIAL_coated_diffuse || m.kind == MCL_MATERIAL_coated_conductor) {  // the layer (no other kind reads it)
        const float layer[3] = {m.thickness, float(m.layerMaxDepth), float(m.layerSamples)};
        append(bytes, layer, sizeof layer);
      }
      if (m.kind == MCL_MATERIAL_coated_conductor) append(bytes, &m.baseAlpha, sizeof m.baseAlpha);
      if (m.kind == MCL_MATERIAL_metal_rough && m.clearcoat > 0.0f) {  // only then: other scenes keep their digests
        const float coat[2] = {m.clearcoat, m.clearcoatRoughness};
        bytes.add("clearcoat");
        append(bytes, coat, sizeof coat);
      }
      if (m.kind == MCL_MATERIAL_metal_rough && m.sheenColor != glm::vec3(0.0f)) {  // only then: as the coat
        bytes.add("sheen");
        appendVec(bytes, m.sheenColor);
        append(bytes, &m.sheenRoughness, sizeof m.sheenRoughness);
      }
      if (m.kind == MCL_MATERIAL_conductor && (m.beckmann || m.conductorFactor != glm::vec3(1.0f))) {
        bytes.add(m.beckmann ? "beckmann" : "ggx");  // only then: other scenes keep their digests
        appendVec(bytes, m.conductorFactor);
      }
    }
  }
  if (scene.environment.enabled) {  // the map by its content
    const EnvironmentDesc& e = scene.environment;
    bytes.add("environment");
    const std::uint64_t map = fileContentHash(e.file, files);
    append(bytes, &map, sizeof map);
    appendVec(bytes, e.radiance);
    append(bytes, &e.scale, sizeof e.scale);
    append(bytes, &e.rotateYDegrees, sizeof e.rotateYDegrees);
    if (e.equalArea) {  // (only pbrt scenes' maps: the others keep their digests)
      bytes.add("equal-area");
      append(bytes, &e.mapFromWorld[0][0], sizeof e.mapFromWorld);
    }
  }
  if (!scene.lights.empty()) {  // (scenes without "lights" keep their digests)
    bytes.add("lights");
    for (const LightDesc& l : scene.lights) {
      bytes.add(std::to_string(int(l.kind)));
      appendVec(bytes, l.position);
      appendVec(bytes, l.direction);
      appendVec(bytes, l.color);
      append(bytes, &l.cutoffDegrees, sizeof l.cutoffDegrees);
      append(bytes, &l.beamDegrees, sizeof l.beamDegrees);
      if (l.kind == PunctualKind::Sun) append(bytes, &l.angleDegrees, sizeof l.angleDegrees);
    }
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
