// gltf_model.h: reading a glTF 2.0 file (.gltf with external or data-URI buffers, or .glb)
// through tinygltf, and its accessors as checked arrays. Files are read through montecl's own
// callbacks (regular files only; nothing expanded, nothing written); images are not decoded here
// (the textures are opened by path later): an image's bytes are only looked at to know whether it
// has a file. Errors are InputError "<file>: <where>: <problem>".
#pragma once
#include <tiny_gltf.h>

#include <glm/glm.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace montecl {

// Loads the model; tinygltf's warnings are appended (one line each, naming the file). opened, when
// given, gets every other file read (external buffers and images) by the path actually opened
// (percent-decoded, resolved). A JSON part nested deeper than kMaxJsonDepth is refused first.
tinygltf::Model readGltfModel(const std::string& path, std::vector<std::string>* warnings,
                              std::vector<std::string>* opened = nullptr);

// The glTF extensions montecl reads; a file that lists any other in extensionsRequired is refused
// with one line naming it (extensionsUsed alone: a warning).
bool gltfExtensionSupported(const std::string& name);

// Which component types an attribute accepts: Any is core glTF's float-or-normalized-unsigned
// rule; Position, Normal and TexCoord add the integer types KHR_mesh_quantization lists for them
// (POSITION and TEXCOORD: signed or unsigned byte / short, normalized or not; NORMAL, and TANGENT
// and the instancing ROTATION, which read Normal: normalized signed byte / short). Normalized signed values are max(c / (2^(b-1) - 1), -1), as glTF defines.
enum class AccessorUse { Any, Position, Normal, TexCoord };

// Accessor `index`, checked to be in range, of type VEC<components> and of a component type `use`
// allows; where names the attribute for messages. readFloatAccessor checks with it, and so do the
// attributes a Draco buffer holds (their accessors have no data, only count, type and component type).
const tinygltf::Accessor& checkFloatAccessor(const std::string& file, const tinygltf::Model& m, int index, int components,
                                             const std::string& where, AccessorUse use);

// An integer component v of an accessor of componentType (BYTE ... UNSIGNED_SHORT) as glTF reads it:
// v itself, or normalized (signed: max(v / (2^(b-1) - 1), -1); unsigned: v / (2^b - 1)).
float gltfIntegerComponent(float v, int componentType, bool normalized);

// Accessor `index` as floats with `components` components per element (VEC2: 2, VEC3: 3, VEC4: 4), from
// FLOAT data or the integer data `use` allows; where names the attribute for messages.
std::vector<float> readFloatAccessor(const std::string& file, const tinygltf::Model& m, int index, int components,
                                     const std::string& where, AccessorUse use = AccessorUse::Any);

// Accessor `index` as vertex indices (SCALAR UNSIGNED_BYTE / SHORT / INT).
std::vector<std::uint32_t> readIndexAccessor(const std::string& file, const tinygltf::Model& m, int index,
                                             const std::string& where);

// The bytes of bufferView `index`, checked to lie inside its buffer; where names the referrer.
struct GltfViewBytes {
  const unsigned char* data;
  std::size_t size;
};
GltfViewBytes gltfBufferViewBytes(const std::string& file, const tinygltf::Model& m, int index, const std::string& where);

// The texture path of image `index`: its file when it has one (a URI that is not a data URI),
// resolved beside the glTF and percent-decoded; for an embedded image (a bufferView, a data URI)
// the name "<file>#images[i].<png|jpg>", its bytes added to scene.embeddedImages. "" for an index
// out of range. Throws InputError for an embedded image in a format montecl does not read.
std::string gltfImagePath(const std::string& file, const tinygltf::Model& m, int index, Scene& scene);

}  // namespace montecl
