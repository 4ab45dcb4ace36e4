// environment_table.h: the device side of the environment light (kernels/shared/environment.h):
// the map's texels (rgb radiance, w = sampling density p(u, v)) and the CDFs of its 2D
// piecewise-constant distribution (luminance * sin(theta) per texel: marginal over rows, then one
// conditional per row, as pbrt's Distribution2D), and what FrameParams says of it.
#pragma once
#include <string>
#include <vector>

#include "kernels/shared/types.h"
#include "scene/scene.h"

namespace montecl {

struct EnvironmentTable {
  std::vector<float4> map{float4(0.0f)};  // never empty (a buffer of one texel when unused)
  std::vector<float> cdf{0.0f};
  uint width = 0, height = 0;             // 0 x 0: constant (or no) environment
  float4 radiance{0.0f};  // FrameParams::environment: rgb radiance (times the map), w 1 when enabled
  float rotateY = 0.0f;   // FrameParams::envRotateY, radians
};

// The table of a width x height map of rgb texels (row 0 at the top). Pure; the tests use it.
EnvironmentTable environmentFromPixels(int width, int height, const std::vector<glm::vec3>& rgb);

// Reads the scene's environment (its map, if any). Throws InputError "<scene>: environment.file: ..." when the map cannot be read, is
// not an image, or holds negative or non-finite values.
EnvironmentTable buildEnvironment(const Scene& scene);

}  // namespace montecl
