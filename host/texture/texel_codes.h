// texel_codes.h: 8-bit storage of a texture level whose half texels are all decodes of 8-bit codes
// (kernels/shared/types.h MCL_TEXELS_SRGB8 / MCL_TEXELS_LINEAR8): the two code tables the texel
// buffer starts with, and the encoder that finds a level's codes. Reads and writes memory only.
#pragma once
#include <cstdint>
#include <vector>

namespace montecl {

// The MCL_TEXEL_TABLES ushorts at the texel buffer's start: the half value of code c's sRGB decode
// at c, of c / 255 at 256 + c (as 8-bit images are read: texture/mip_chain.cpp).
const std::vector<std::uint16_t>& texelCodeTables();

// The format a level of half texels (4 ushorts a texel: r, g, b, a) can be stored in: with every
// r, g, b the half of an sRGB code's decode and every a the half of a linear one, MCL_TEXELS_SRGB8;
// with every channel linear, MCL_TEXELS_LINEAR8 (each texel then two ushorts, r | g << 8 and
// b | a << 8, written to *codes); else MCL_TEXELS_HALF (codes left empty). Decoding the codes
// through the tables gives back every half bit for bit.
std::uint32_t encodeTexelCodes(const std::vector<std::uint16_t>& half, std::vector<std::uint16_t>* codes);

}  // namespace montecl
