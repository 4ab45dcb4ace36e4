// gltf_accessor_cache.cpp: decodes a glTF accessor once while primitives keep sharing it
// (gltf_accessor_cache.h). Reads the model's buffers; writes nothing.
#include "scene/gltf_accessor_cache.h"

namespace montecl {

const std::vector<float>& GltfAccessorCache::floats(const std::string& slot, const std::string& file,
                                                    const tinygltf::Model& m, int index, int components,
                                                    const std::string& where, AccessorUse use) {
  Floats& f = floats_[slot];
  if (f.index != index || f.components != components || f.use != use) {
    f.index = -1;  // a read that throws leaves the slot empty
    f.values = readFloatAccessor(file, m, index, components, where, use);
    f.index = index, f.components = components, f.use = use;
  }
  return f.values;
}

const std::vector<std::uint32_t>& GltfAccessorCache::indices(const std::string& file, const tinygltf::Model& m,
                                                             int index, const std::string& where) {
  if (indexAccessor_ != index) {
    indexAccessor_ = -1;
    indices_ = readIndexAccessor(file, m, index, where);
    indexAccessor_ = index;
  }
  return indices_;
}

}  // namespace montecl
