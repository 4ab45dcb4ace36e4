// gltf_texture_info.h: how a glTF textureInfo is read: its KHR_texture_transform (offset, rotation,
// scale, texCoord override) and its sampler's wrapS / wrapT, as a TextureSampling in montecl's UV
// convention, and which TEXCOORD_n set it reads. Bad values are InputError naming the key.
#pragma once
#include <tiny_gltf.h>

#include <string>

#include "scene/scene.h"

namespace montecl {

struct GltfTextureRead {
  TextureSampling sampling;
  int texCoord = 0;  // the TEXCOORD_n set (the extension's texCoord when it gives one)
};

// info: the textureInfo's extensions and texCoord; where: its key ("materials[0].emissiveTexture").
GltfTextureRead readGltfTextureInfo(const std::string& file, const tinygltf::Model& m, int texture, int texCoord,
                                    const tinygltf::ExtensionMap& extensions, const std::string& where);

// Throws InputError for a sampler whose wrapS or wrapT is not one of glTF's three modes.
void checkGltfSamplers(const std::string& file, const tinygltf::Model& m);

}  // namespace montecl
