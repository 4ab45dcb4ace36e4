// texture_budget.h: which finest mip levels to drop so that every texture fits a byte budget.
// Reads level sizes; writes nothing. Pure.
#pragma once
#include <cstdint>
#include <vector>

namespace montecl {

// levelBytes[t][k]: bytes of mip level k of texture t (level 0 the finest). Returns, per texture,
// how many finest levels to drop: repeatedly the finest kept level of the texture whose finest
// kept level is the largest (the lowest index on a tie) until the kept levels fit budget; every
// texture keeps at least its coarsest level (so the result may still exceed a tiny budget).
std::vector<int> finestLevelsToDrop(const std::vector<std::vector<std::uint64_t>>& levelBytes,
                                    std::uint64_t budget);

}  // namespace montecl
