// bump_gradient.h: a height map's gradient texture for bump mapping (kernels/shared/bump_map.h).
// Reads a linear RGBA image (mip_chain.h, rows bottom to top); writes per texel the scaled height
// gradient per unit of UV, (s dh/du, s dh/dv, 0, 1), h the mean of R, G and B.
#pragma once
#include <cstdint>

#include "texture/mip_chain.h"

namespace montecl {

// Central differences over the two neighbours of each texel, found through the texture's wrap
// modes (MCL_WRAP_*: repeat, clamp, mirrored repeat) and divided by their distance in UV: a linear
// ramp gives its slope exactly, also at clamped edges (one-sided there). Values are kept within
// the half-float range (the texels are stored as half floats).
RgbaImage bumpGradient(const RgbaImage& heights, float scale, std::uint32_t wrapS, std::uint32_t wrapT);

}  // namespace montecl
