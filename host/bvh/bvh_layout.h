// bvh_layout.h: which BVH the kernels traverse (--bvh-layout auto|wide|binary). wide: the 8-wide
// BVH (Bvh::wideNodes(), float8 tests of eight boxes; best on CPUs); binary: the binary BVH
// (Bvh::nodes, two child boxes per visit, 64-entry stack; suited to GPUs); auto: binary on GPU devices, wide
// otherwise. Both layouts give the same hits. Reads and writes nothing.
#pragma once
#include <cstddef>
#include <string>

namespace montecl {

struct Bvh;

enum class BvhLayout { Auto, Wide, Binary };

// "auto" | "wide" | "binary"; throws InputError otherwise.
BvhLayout parseBvhLayout(const std::string& name);
const char* bvhLayoutName(BvhLayout layout);
// Auto becomes Binary on a GPU and Wide elsewhere; Wide and Binary are returned as they are.
BvhLayout resolveBvhLayout(BvhLayout layout, bool isGpu);
// Bytes of the node array a resolved layout traverses (Bvh::wideNodes() or Bvh::nodes).
std::size_t bvhNodeBytes(const Bvh& bvh, BvhLayout resolved);

}  // namespace montecl
