// gltf_texture_info.cpp: a glTF textureInfo's transform and wrap modes (gltf_texture_info.h).
#include "scene/gltf_texture_info.h"

#include <cmath>

#include "scene/load_util.h"
#include "scene/value_limits.h"

namespace montecl {
namespace {

std::uint32_t wrapMode(int gl) {
  return gl == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE ? 1u : gl == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? 2u : 0u;
}

bool knownWrap(int gl) {
  return gl == TINYGLTF_TEXTURE_WRAP_REPEAT || gl == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE ||
         gl == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
}

// A finite number, or an array of n finite numbers, under key of the extension object.
double number(const std::string& file, const tinygltf::Value& v, const std::string& key) {
  if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble())) loadFail(file, key, "must be a finite number");
  return v.GetNumberAsDouble();
}

void pair(const std::string& file, const tinygltf::Value& o, const char* name, const std::string& where, double out[2]) {
  if (!o.Has(name)) return;
  const tinygltf::Value& v = o.Get(name);
  const std::string key = where + "." + name;
  if (!v.IsArray() || v.ArrayLen() != 2) loadFail(file, key, "must be an array of 2 numbers");
  for (int i = 0; i < 2; ++i) out[i] = number(file, v.Get(i), key);
  // 1e300 became an infinite float UV: a black texture, and albedo AOVs that failed the render.
  const std::string bad = magnitudeProblem(glm::dvec3(out[0], out[1], 0.0), kMaxTextureTransform,
                                           "a float UV past it keeps no texel position");
  if (!bad.empty()) loadFail(file, key, bad);
}

}  // namespace

void checkGltfSamplers(const std::string& file, const tinygltf::Model& m) {
  for (std::size_t i = 0; i < m.samplers.size(); ++i) {
    const tinygltf::Sampler& s = m.samplers[i];
    const std::string where = "samplers[" + std::to_string(i) + "]";
    if (!knownWrap(s.wrapS))
      loadFail(file, where + ".wrapS", "unknown wrap mode " + std::to_string(s.wrapS) + " (10497, 33071 or 33648)");
    if (!knownWrap(s.wrapT))
      loadFail(file, where + ".wrapT", "unknown wrap mode " + std::to_string(s.wrapT) + " (10497, 33071 or 33648)");
  }
}

GltfTextureRead readGltfTextureInfo(const std::string& file, const tinygltf::Model& m, int texture, int texCoord,
                                    const tinygltf::ExtensionMap& extensions, const std::string& where) {
  GltfTextureRead r;
  r.texCoord = texCoord;
  if (texCoord < 0) loadFail(file, where + ".texCoord", "must be a whole number >= 0");
  const tinygltf::Texture& t = m.textures[static_cast<std::size_t>(texture)];
  if (t.sampler >= 0 && static_cast<std::size_t>(t.sampler) < m.samplers.size()) {
    const tinygltf::Sampler& s = m.samplers[static_cast<std::size_t>(t.sampler)];
    r.sampling.wrapS = wrapMode(s.wrapS);
    r.sampling.wrapT = wrapMode(s.wrapT);
  }
  const auto ext = extensions.find("KHR_texture_transform");
  if (ext == extensions.end()) return r;
  const tinygltf::Value& o = ext->second;
  const std::string key = where + ".extensions.KHR_texture_transform";
  if (!o.IsObject()) loadFail(file, key, "must be an object");
  double offset[2] = {0.0, 0.0}, scale[2] = {1.0, 1.0}, rotation = 0.0;
  pair(file, o, "offset", key, offset);
  pair(file, o, "scale", key, scale);
  if (o.Has("rotation")) rotation = number(file, o.Get("rotation"), key + ".rotation");
  if (o.Has("texCoord")) {
    const tinygltf::Value& v = o.Get("texCoord");
    if (!v.IsInt() || v.Get<int>() < 0) loadFail(file, key + ".texCoord", "must be a whole number >= 0");
    r.texCoord = v.Get<int>();
  }
  // The extension's matrix T(offset) R(rotation) S(scale) acts on glTF's UVs (v down); montecl's
  // are (u, 1 - v) on both sides, which gives these rows.
  const double c = std::cos(rotation), s = std::sin(rotation);
  const double sx = scale[0], sy = scale[1], ox = offset[0], oy = offset[1];
  r.sampling.row0 = glm::vec3(float(c * sx), float(-s * sy), float(s * sy + ox));
  r.sampling.row1 = glm::vec3(float(s * sx), float(c * sy), float(1.0 - c * sy - oy));
  return r;
}

}  // namespace montecl
