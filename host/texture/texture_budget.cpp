// texture_budget.cpp: greedy choice of the mip levels the texture budget drops (texture_budget.h).
#include "texture/texture_budget.h"

namespace montecl {

std::vector<int> finestLevelsToDrop(const std::vector<std::vector<std::uint64_t>>& levelBytes,
                                    std::uint64_t budget) {
  std::vector<int> drop(levelBytes.size(), 0);
  std::uint64_t total = 0;
  for (const auto& levels : levelBytes)
    for (std::uint64_t b : levels) total += b;
  while (total > budget) {
    int best = -1;
    for (std::size_t t = 0; t < levelBytes.size(); ++t) {
      if (drop[t] + 1 >= int(levelBytes[t].size())) continue;  // only the coarsest level left
      if (best < 0 || levelBytes[t][drop[t]] > levelBytes[best][drop[best]]) best = int(t);
    }
    if (best < 0) break;
    total -= levelBytes[best][drop[best]];
    ++drop[best];
  }
  return drop;
}

}  // namespace montecl
