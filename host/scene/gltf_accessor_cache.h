// gltf_accessor_cache.h: the last accessor a glTF loader decoded for each attribute, kept so that
// primitives sharing one accessor (an exporter's 20,000 primitives over one POSITION) decode it
// once, not once each (which cost minutes of CPU). Reads the model's buffers; writes nothing.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "scene/gltf_model.h"

namespace montecl {

class GltfAccessorCache {
 public:
  // readFloatAccessor(file, m, index, components, where, use), decoded again only when `slot`
  // (the attribute's name) last held another accessor or reading. The reference stays valid until
  // the same slot is asked for another one.
  const std::vector<float>& floats(const std::string& slot, const std::string& file, const tinygltf::Model& m,
                                   int index, int components, const std::string& where, AccessorUse use);
  // readIndexAccessor(file, m, index, where), likewise for the last index accessor.
  const std::vector<std::uint32_t>& indices(const std::string& file, const tinygltf::Model& m, int index,
                                            const std::string& where);

 private:
  struct Floats {
    int index = -1, components = 0;
    AccessorUse use = AccessorUse::Any;
    std::vector<float> values;
  };
  std::map<std::string, Floats> floats_;
  int indexAccessor_ = -1;
  std::vector<std::uint32_t> indices_;
};

}  // namespace montecl
