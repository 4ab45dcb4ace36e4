// gltf_draco.h: KHR_draco_mesh_compression: a primitive's Draco buffer (the extension's bufferView)
// decoded with the Draco library into what plain accessors would hold: the attributes the
// extension maps (glTF name -> Draco unique id) as floats, and the triangles' indices.
#pragma once
#include <tiny_gltf.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace montecl {

struct GltfDracoMesh {
  // glTF attribute name -> its values, as many per vertex as its accessor's type has components;
  // dequantized by Draco, integer accessors' values read as glTF reads them (normalized or not).
  std::map<std::string, std::vector<float>> attributes;
  std::vector<std::uint32_t> indices;  // the decoded faces, three per triangle
};

// tinygltf 2.7, built without Draco, refuses a primitive whose indices accessor has no bufferView,
// as every Draco primitive's is. hideGltfDracoIndices takes "indices" out of the JSON text of each
// primitive with the extension whose indices accessor has no bufferView, noting them in hidden
// (false, text untouched, when there is none); restoreGltfDracoIndices puts them back into the
// model tinygltf made of that text.
struct GltfHiddenIndices {
  std::size_t mesh, primitive;
  int accessor;
};
bool hideGltfDracoIndices(std::string& jsonText, std::vector<GltfHiddenIndices>& hidden);
// The same on a GLB's JSON chunk (the file rewritten with the new chunk, the BIN chunk as it was).
bool hideGltfDracoIndicesInGlb(std::string& glbBytes, std::vector<GltfHiddenIndices>& hidden);
void restoreGltfDracoIndices(tinygltf::Model& m, const std::vector<GltfHiddenIndices>& hidden);

// Whether the primitive has the extension.
bool hasGltfDraco(const tinygltf::Primitive& p);

// Decodes p's Draco buffer. Every problem (a bufferView out of its buffer, a buffer Draco cannot
// decode, an attribute id the buffer lacks, an accessor whose count or component count disagrees
// with the decoded mesh, a mode other than TRIANGLES) is an InputError naming file and where (the
// primitive, "meshes[i].primitives[j]").
GltfDracoMesh decodeGltfDraco(const std::string& file, const tinygltf::Model& m, const tinygltf::Primitive& p,
                              const std::string& where);

}  // namespace montecl
