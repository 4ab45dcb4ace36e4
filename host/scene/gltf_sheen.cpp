// gltf_sheen.cpp: applyGltfSheen (gltf_sheen.h): reads a glTF material's KHR_materials_sheen
// object, writes the MaterialDesc's sheen.
#include "scene/gltf_sheen.h"

namespace montecl {
namespace {

const char* const kSheen = "KHR_materials_sheen";

[[noreturn]] void sheenFail(const std::string& file, const std::string& where, const char* key, const char* problem) {
  loadFail(file, where + ".extensions." + kSheen + "." + key, problem);
}

// A number in [0, 1], or fails naming key.
float unitNumber(const std::string& file, const std::string& where, const tinygltf::Value& v, const char* key) {
  const double x = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
  if (!(x >= 0.0 && x <= 1.0)) sheenFail(file, where, key, "must be a number in [0, 1]");
  return float(x);
}

}  // namespace

bool gltfSheenExtension(const std::string& name) { return name == kSheen; }

void applyGltfSheen(const std::string& file, const std::string& where, const tinygltf::Material& g, MaterialDesc& d,
                    KindWarnings& unused) {
  const auto it = g.extensions.find(kSheen);
  if (it == g.extensions.end()) return;
  const tinygltf::Value& ext = it->second;
  if (!ext.IsObject()) loadFail(file, where + ".extensions." + kSheen, "must be an object");
  glm::vec3 color(0.0f);
  if (ext.Has("sheenColorFactor")) {
    const tinygltf::Value& v = ext.Get("sheenColorFactor");
    if (!v.IsArray() || v.ArrayLen() != 3) sheenFail(file, where, "sheenColorFactor", "must be an array of 3 numbers in [0, 1]");
    for (int c = 0; c < 3; ++c) {
      const double x = v.Get(c).IsNumber() ? v.Get(c).GetNumberAsDouble() : -1.0;
      if (!(x >= 0.0 && x <= 1.0)) sheenFail(file, where, "sheenColorFactor", "must be an array of 3 numbers in [0, 1]");
      color[c] = float(x);
    }
  }
  const float roughness = ext.Has("sheenRoughnessFactor") ? unitNumber(file, where, ext.Get("sheenRoughnessFactor"), "sheenRoughnessFactor") : 0.0f;
  if (color == glm::vec3(0.0f)) return;  // the extension's "the whole sheen layer is disabled"
  if (d.kind == MCL_MATERIAL_dielectric || d.kind == MCL_MATERIAL_thin_dielectric) {
    unused.add("sheen on glass", where, std::string(kSheen) + " on a fully transmissive material not used (no sheen on glass)");
    return;
  }
  if (d.kind == MCL_MATERIAL_diffuse) d.kind = MCL_MATERIAL_metal_rough;  // glTF's BRDF of these factors, under sheen
  d.sheenColor = color;
  d.sheenRoughness = roughness;
  // The material table has no room for two more texture indices: the factors alone are used.
  if (ext.Has("sheenColorTexture") || ext.Has("sheenRoughnessTexture"))
    unused.add("sheen textures", where, "sheenColorTexture and sheenRoughnessTexture not read by montecl (the factors alone are used)");
  if (d.transmission > 0.0f)
    unused.add("sheen over transmission", where, "the sheen covers the reflecting part only (the transmitted part is glass without sheen)");
}

}  // namespace montecl
