// bvh_layout.cpp: --bvh-layout names, the auto choice by device type, and node bytes per layout.
#include "bvh/bvh_layout.h"

#include "bvh/bvh.h"
#include "util/errors.h"

namespace montecl {

BvhLayout parseBvhLayout(const std::string& name) {
  if (name == "auto") return BvhLayout::Auto;
  if (name == "wide") return BvhLayout::Wide;
  if (name == "binary") return BvhLayout::Binary;
  throw InputError("--bvh-layout: \"" + name + "\" is not auto, wide or binary");
}

const char* bvhLayoutName(BvhLayout layout) {
  switch (layout) {
    case BvhLayout::Wide: return "wide";
    case BvhLayout::Binary: return "binary";
    default: return "auto";
  }
}

BvhLayout resolveBvhLayout(BvhLayout layout, bool isGpu) {
  if (layout != BvhLayout::Auto) return layout;
  return isGpu ? BvhLayout::Binary : BvhLayout::Wide;
}

std::size_t bvhNodeBytes(const Bvh& bvh, BvhLayout resolved) {
  return resolved == BvhLayout::Binary ? bvh.nodes.size() * sizeof(BvhNode) : bvh.wideNodes().size() * sizeof(WideNode);
}

}  // namespace montecl
