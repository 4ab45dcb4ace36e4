// environment_table.cpp: loads the environment map (image/exr_layers.h: EXR, HDR or any format
// OpenImageIO reads) and builds its sampling tables (environment_table.h), in double, stored as float.
#include "render/environment_table.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "image/exr_layers.h"
#include "scene/equal_area.h"
#include "util/host_memory.h"
#include "util/errors.h"

namespace montecl {

EnvironmentTable environmentFromPixels(int width, int height, const std::vector<glm::vec3>& rgb) {
  EnvironmentTable t;
  t.width = uint(width);
  t.height = uint(height);
  const std::size_t w = std::size_t(width), h = std::size_t(height);
  std::vector<double> weight(w * h);
  double total = 0.0;
  for (std::size_t y = 0; y < h; ++y) {
    const double sinTheta = std::sin(M_PI * (double(y) + 0.5) / double(h));
    for (std::size_t x = 0; x < w; ++x) {
      const glm::vec3& c = rgb[y * w + x];
      weight[y * w + x] = (0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z) * sinTheta;
      total += weight[y * w + x];
    }
  }
  if (!(total > 0.0))  // a black map: sample by solid angle (its radiance is 0 anyway)
    for (std::size_t y = 0; y < h; ++y)
      for (std::size_t x = 0; x < w; ++x) total += weight[y * w + x] = std::sin(M_PI * (double(y) + 0.5) / double(h));
  const double mean = total / double(w * h);
  t.map.resize(w * h);
  for (std::size_t i = 0; i < w * h; ++i) t.map[i] = float4(rgb[i], float(weight[i] / mean));
  t.cdf.assign((h + 1) + h * (w + 1), 0.0f);
  double rowsSoFar = 0.0;
  for (std::size_t y = 0; y < h; ++y) {
    double rowTotal = 0.0;
    for (std::size_t x = 0; x < w; ++x) rowTotal += weight[y * w + x];
    float* row = &t.cdf[(h + 1) + y * (w + 1)];
    double sum = 0.0;
    for (std::size_t x = 0; x < w; ++x) {
      row[x] = rowTotal > 0.0 ? float(sum / rowTotal) : float(double(x) / double(w));
      sum += weight[y * w + x];
    }
    row[w] = 1.0f;
    t.cdf[y] = float(rowsSoFar / total);
    rowsSoFar += rowTotal;
  }
  t.cdf[h] = 1.0f;
  return t;
}

EnvironmentTable buildEnvironment(const Scene& scene) {
  const EnvironmentDesc& env = scene.environment;
  if (!env.enabled) return EnvironmentTable{};
  EnvironmentTable constant;
  constant.radiance = float4(env.radiance * env.scale, 1.0f);
  constant.rotateY = float(double(env.rotateYDegrees) * M_PI / 180.0);
  if (env.file.empty()) return constant;
  const std::string where = "environment.file";
  LayeredImage image;
  try {
    // Beyond the decode: the RGB copy, the sampling weights and the CDF rows (about 24 bytes).
    image = readLayeredImage(env.file, [](int w, int h, int c) { return decodeMemoryRefusal(w, h, c, 24); });
  } catch (const InputError& e) {
    throwInputError(scene.path, where, e.what());
  }
  // R, G, B by name, else the first three channels, else one channel as grey.
  const std::vector<float>* planes[3] = {image.find("R"), image.find("G"), image.find("B")};
  if (!planes[0] || !planes[1] || !planes[2]) {
    for (int c = 0; c < 3; ++c)
      planes[c] = &image.planes[std::min<std::size_t>(std::size_t(c), image.planes.size() - 1)];
  }
  const std::string bad = badPixelValue({planes[0], planes[1], planes[2]}, image.width, FLT_MAX);
  if (!bad.empty()) throwInputError(scene.path, where, "'" + env.file + "': " + bad);
  const std::size_t count = image.pixelCount();
  std::vector<glm::vec3> rgb(count);
  for (std::size_t i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) rgb[i][c] = (*planes[c])[i];
  int width = image.width, height = image.height;
  if (env.equalArea) {  // a pbrt-v4 map (scene/equal_area.h)
    if (width != height)
      throwInputError(scene.path, where, "'" + env.file + "': pbrt-v4's equal-area map must be square, got " +
                                             std::to_string(width) + " x " + std::to_string(height));
    rgb = latLongFromEqualArea(rgb, width, env.mapFromWorld, width, height);
  }
  EnvironmentTable t = environmentFromPixels(width, height, rgb);
  t.radiance = constant.radiance;
  t.rotateY = constant.rotateY;
  return t;
}

}  // namespace montecl
