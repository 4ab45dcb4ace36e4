// equal_area.h: pbrt-v4's environment maps: its equal-area octahedral sphere-to-square mapping
// (Clarberg's, pbrt-v4 EqualAreaSphereToSquare) and the resampling of such a square map into
// montecl's latitude-longitude convention (kernels/shared/environment.h). Reads and writes pixel
// arrays only.
#pragma once
#include <glm/glm.hpp>

#include <vector>

namespace montecl {

// The point of [0, 1]^2 where pbrt-v4 stores the radiance arriving from unit direction d: +z at
// the centre, -z at the corners, +x at (1, 0.5), +y at (0.5, 1) (row y = 1 is the image's last).
glm::dvec2 equalAreaSphereToSquare(const glm::dvec3& d);

// The largest side of the latitude-longitude map made from an equal-area one (2 side x side):
// 2048 keeps it at 4096 x 2048 texels (134 MB of float4 on the device).
constexpr int kMaxEqualAreaResample = 2048;

// A square equal-area map of `side` x `side` texels (rgb, row 0 first) as a latitude-longitude
// map of 2 n x n texels, n = min(side, kMaxEqualAreaResample): each texel takes the nearest square
// texel (as pbrt-v4 looks its map up) in the direction mapFromWorld * (its centre's direction).
std::vector<glm::vec3> latLongFromEqualArea(const std::vector<glm::vec3>& square, int side, const glm::dmat3& mapFromWorld,
                                            int& width, int& height);

}  // namespace montecl
