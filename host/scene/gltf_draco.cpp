// gltf_draco.cpp: decodeGltfDraco(): a KHR_draco_mesh_compression buffer through draco::Decoder
// into floats and indices, checked against the primitive's accessors (see gltf_draco.h).
#include "scene/gltf_draco.h"

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>

#include "scene/gltf_model.h"
#include "scene/load_util.h"

namespace montecl {
namespace {

const char* const kDracoExtension = "KHR_draco_mesh_compression";

int accessorComponents(int type) {
  return type == TINYGLTF_TYPE_SCALAR ? 1 : type == TINYGLTF_TYPE_VEC2 ? 2 : type == TINYGLTF_TYPE_VEC3 ? 3
       : type == TINYGLTF_TYPE_VEC4 ? 4 : 0;
}

std::string dracoMessage(const draco::Status& s) {
  std::string msg = s.error_msg_string();
  while (!msg.empty() && (msg.back() == '.' || msg.back() == '\n')) msg.pop_back();
  return oneLine(msg.empty() ? "unknown Draco error" : msg, 120);
}

// One decoded attribute's values per point, as the accessor `a` reads them: Draco converts to float
// for a FLOAT accessor (dequantizing); an integer accessor's values are taken as integers and
// read by glTF's rule.
std::vector<float> dracoValues(const std::string& file, const draco::Mesh& mesh, const draco::PointAttribute& att,
                               const tinygltf::Accessor& a, int components, const std::string& where) {
  const std::size_t n = mesh.num_points();
  std::vector<float> out(n * std::size_t(components));
  const bool isFloat = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  std::int32_t ints[4] = {0, 0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    const draco::AttributeValueIndex v = att.mapped_index(draco::PointIndex(static_cast<std::uint32_t>(i)));
    float* f = &out[i * std::size_t(components)];
    const bool ok = v.value() < att.size() &&
                    (isFloat ? att.ConvertValue<float>(v, static_cast<std::int8_t>(components), f)
                             : att.ConvertValue<std::int32_t>(v, static_cast<std::int8_t>(components), ints));
    if (!ok) loadFail(file, where, "point " + std::to_string(i) + " has no value the accessor's component type can hold");
    for (int c = 0; c < components; ++c) {
      if (!isFloat) f[c] = gltfIntegerComponent(float(ints[c]), a.componentType, a.normalized);
      if (!std::isfinite(f[c])) loadFail(file, where, "element " + std::to_string(i) + " is not finite");
    }
  }
  return out;
}

}  // namespace

bool hideGltfDracoIndices(std::string& jsonText, std::vector<GltfHiddenIndices>& hidden) {
  if (jsonText.find(kDracoExtension) == std::string::npos) return false;  // most files: not parsed again
  nlohmann::json j = nlohmann::json::parse(jsonText, nullptr, false);
  if (!j.is_object() || !j.contains("meshes") || !j["meshes"].is_array()) return false;
  const nlohmann::json none;
  const nlohmann::json& accessors = j.contains("accessors") ? j["accessors"] : none;
  for (std::size_t i = 0; i < j["meshes"].size(); ++i) {
    nlohmann::json& mesh = j["meshes"][i];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (std::size_t k = 0; k < mesh["primitives"].size(); ++k) {
      nlohmann::json& p = mesh["primitives"][k];
      if (!p.is_object() || !p.contains("indices") || !p["indices"].is_number_unsigned()) continue;
      const auto ext = p.find("extensions");
      if (ext == p.end() || !ext->is_object() || !ext->contains(kDracoExtension)) continue;
      const std::size_t a = p["indices"].get<std::size_t>();
      if (!accessors.is_array() || a >= accessors.size() || !accessors[a].is_object() || accessors[a].contains("bufferView"))
        continue;  // tinygltf reports what is wrong with it
      hidden.push_back({i, k, static_cast<int>(a)});
      p.erase("indices");
    }
  }
  if (hidden.empty()) return false;
  try {
    jsonText = j.dump();
  } catch (const nlohmann::json::exception&) {  // a string it cannot write back: tinygltf reports the file
    hidden.clear();
    return false;
  }
  return true;
}

bool hideGltfDracoIndicesInGlb(std::string& bytes, std::vector<GltfHiddenIndices>& hidden) {
  if (bytes.size() < 20) return false;
  std::uint32_t total = 0, length = 0;  // the header's total length, the JSON chunk's
  std::memcpy(&total, bytes.data() + 8, 4);
  std::memcpy(&length, bytes.data() + 12, 4);
  const std::uint64_t end = std::min<std::uint64_t>(total, bytes.size());
  if (20ull + length > end) return false;  // tinygltf reports it
  std::string json = bytes.substr(20, length);
  if (!hideGltfDracoIndices(json, hidden)) return false;
  while (json.size() % 4) json += ' ';  // chunks stay 4-byte aligned
  const std::string rest = bytes.substr(20 + length, std::size_t(end) - 20 - length);
  const auto u32 = [](std::size_t v) {
    const std::uint32_t x = static_cast<std::uint32_t>(v);
    return std::string(reinterpret_cast<const char*>(&x), 4);
  };
  bytes = bytes.substr(0, 8) + u32(20 + json.size() + rest.size()) + u32(json.size()) + bytes.substr(16, 4) + json + rest;
  return true;
}

void restoreGltfDracoIndices(tinygltf::Model& m, const std::vector<GltfHiddenIndices>& hidden) {
  for (const GltfHiddenIndices& h : hidden)
    if (h.mesh < m.meshes.size() && h.primitive < m.meshes[h.mesh].primitives.size())
      m.meshes[h.mesh].primitives[h.primitive].indices = h.accessor;
}

bool hasGltfDraco(const tinygltf::Primitive& p) { return p.extensions.count(kDracoExtension) != 0; }

GltfDracoMesh decodeGltfDraco(const std::string& file, const tinygltf::Model& m, const tinygltf::Primitive& p,
                              const std::string& where) {
  const std::string key = where + ".extensions." + kDracoExtension;
  const tinygltf::Value& ext = p.extensions.at(kDracoExtension);
  if (!ext.IsObject()) loadFail(file, key, "must be an object");
  const int mode = p.mode == -1 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES)
    loadFail(file, where, "mode " + std::to_string(mode) + " with " + kDracoExtension + ": a Draco mesh is a list of triangles (mode 4)");
  const tinygltf::Value& view = ext.Get("bufferView");
  if (!view.IsInt()) loadFail(file, key + ".bufferView", "must be a bufferView index");
  const tinygltf::Value& attributes = ext.Get("attributes");
  if (!attributes.IsObject()) loadFail(file, key + ".attributes", "must be an object (glTF attribute -> Draco id)");
  const GltfViewBytes bytes = gltfBufferViewBytes(file, m, view.Get<int>(), key + ".bufferView");

  // Draco reports a buffer it cannot read as a Status; a count it would allocate for and cannot is
  // an exception from the standard library: both are the file's fault.
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes.data), bytes.size);
  std::unique_ptr<draco::Mesh> mesh;
  try {
    draco::Decoder decoder;
    draco::StatusOr<std::unique_ptr<draco::Mesh>> decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
      loadFail(file, key, "Draco buffer (bufferView " + std::to_string(view.Get<int>()) +
                              ") cannot be decoded: " + dracoMessage(decoded.status()));
    mesh = std::move(decoded).value();
  } catch (const std::bad_alloc&) {
    loadFail(file, key, "Draco buffer declares more data than fits in memory");
  } catch (const std::length_error&) {
    loadFail(file, key, "Draco buffer declares more data than fits in memory");
  }
  if (!mesh) loadFail(file, key, "Draco buffer holds no mesh");

  GltfDracoMesh out;
  const std::size_t points = mesh->num_points();
  for (const std::string& name : attributes.Keys()) {
    const std::string at = key + ".attributes." + oneLine(name, 40);
    const tinygltf::Value& id = attributes.Get(name);
    if (!id.IsInt() || id.Get<int>() < 0) loadFail(file, at, "must be a Draco attribute id (a whole number >= 0)");
    const auto accessor = p.attributes.find(name);
    if (accessor == p.attributes.end())
      loadFail(file, at, "names " + oneLine(name, 40) + ", which the primitive's attributes do not have");
    if (accessor->second < 0 || static_cast<std::size_t>(accessor->second) >= m.accessors.size())
      loadFail(file, where + "." + oneLine(name, 40), "accessor index " + std::to_string(accessor->second) + " out of range");
    const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(accessor->second)];
    const draco::PointAttribute* att = mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id.Get<int>()));
    if (!att) loadFail(file, at, "the Draco buffer has no attribute with id " + std::to_string(id.Get<int>()));
    if (!att->is_mapping_identity() && att->indices_map_size() < points)
      loadFail(file, at, "the Draco attribute maps fewer points than the mesh has");
    const int components = accessorComponents(a.type);
    if (components == 0 || components != att->num_components())
      loadFail(file, at, "accessor " + std::to_string(accessor->second) + " has " + std::to_string(components) +
                             " components per element, the Draco attribute " + std::to_string(att->num_components()));
    if (a.count != points)
      loadFail(file, at, "accessor " + std::to_string(accessor->second) + " says " + std::to_string(a.count) +
                             " elements, the Draco buffer decodes " + std::to_string(points) + " points");
    out.attributes[name] = dracoValues(file, *mesh, *att, a, components, at);
  }
  const std::size_t faces = mesh->num_faces();
  if (p.indices >= 0) {
    if (static_cast<std::size_t>(p.indices) >= m.accessors.size())
      loadFail(file, where + ".indices", "accessor index " + std::to_string(p.indices) + " out of range");
    const std::size_t count = m.accessors[static_cast<std::size_t>(p.indices)].count;
    if (count != 3 * faces)
      loadFail(file, where + ".indices", "accessor " + std::to_string(p.indices) + " says " + std::to_string(count) +
                                             " indices, the Draco buffer decodes " + std::to_string(faces) + " triangles");
  }
  out.indices.reserve(3 * faces);
  for (std::uint32_t f = 0; f < faces; ++f)
    for (const draco::PointIndex& v : mesh->face(draco::FaceIndex(f))) out.indices.push_back(v.value());
  return out;
}

}  // namespace montecl
