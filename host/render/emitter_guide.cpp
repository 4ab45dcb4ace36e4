// emitter_guide.cpp: the emitter pick's guide table (emitter_guide.h): per bucket, the pick of the
// bucket's smallest u, found with the device's own bucket arithmetic so the table is exact.
#include "render/emitter_guide.h"

#include <cmath>
#include <limits>

#include "kernels/shared/lights.h"

namespace montecl {

void fillEmitterGuide(std::vector<Emitter>& emitters) {
  const std::uint32_t count = static_cast<std::uint32_t>(emitters.size());
  if (count == 0) return;
  emitters[0].guide = 0;  // bucket 0 starts at -infinity, which every cdf exceeds
  for (std::uint32_t b = 1; b < count; ++b) {
    // The smallest float u whose bucket is b: start near b / count and step by one ulp until the
    // bucket of u is b and the bucket of the float below it is not.
    float u = static_cast<float>(double(b) / double(count));
    const float down = -std::numeric_limits<float>::infinity(), up = std::numeric_limits<float>::infinity();
    while (emitter_guide_bucket(count, u) < b) u = std::nextafter(u, up);
    while (emitter_guide_bucket(count, std::nextafter(u, down)) >= b) u = std::nextafter(u, down);
    emitters[b].guide = pick_emitter_between(emitters.data(), 0u, count - 1u, u);  // the whole table
  }
}

}  // namespace montecl
