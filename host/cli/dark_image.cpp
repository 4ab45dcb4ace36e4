// dark_image.cpp: darkImageWarning (dark_image.h): the image's 99th-percentile luminance, and the
// likeliest reason for a dark one from the scene's lights and environment.
#include "cli/dark_image.h"

#include <algorithm>
#include <cstdio>

#include "scene/render_choices.h"

namespace montecl {

std::string darkImageWarning(const std::vector<float>& rgb, const Scene& scene) {
  const std::size_t n = rgb.size() / 3;
  if (n == 0) return "";
  std::vector<float> lum(n);
  for (std::size_t i = 0; i < n; ++i)
    lum[i] = 0.2126f * rgb[3 * i] + 0.7152f * rgb[3 * i + 1] + 0.0722f * rgb[3 * i + 2];
  // A few bright pixels (a lamp's bulb, two headlights) on black still read as a black frame.
  const std::size_t k = std::min(n - 1, n * 99 / 100);
  std::nth_element(lum.begin(), lum.begin() + std::ptrdiff_t(k), lum.end());
  const float p99 = lum[k];
  if (!(p99 < 0.01f)) return "";
  std::string text = scene.path + ": the image is nearly black (99% of its pixels below 1% of white): ";
  const EnvironmentDesc& env = scene.environment;
  if (scene.render.integrator == Integrator::Ao)
    return text + "ambient occlusion sees little of the model; --view or --camera frames it";
  if (!env.enabled)
    return text + "no environment lights it, only the scene's own lights" +
           (scene.lights.empty() ? std::string() : " (" + std::to_string(scene.lights.size()) + ")") +
           ", which light little of what the camera sees; --env 1,1,1 adds a white sky (or a map file), "
           "--view or --camera looks elsewhere";
  char sky[96];
  std::snprintf(sky, sizeof sky, "%g", double(std::max({env.radiance.x, env.radiance.y, env.radiance.z}) * env.scale));
  return text + "the environment (radiance " + (env.file.empty() ? std::string(sky) : "map x " + std::string(sky)) +
         ") is dim or hidden from what the camera sees; --env-scale raises it, --env 1,1,1 replaces it, --view "
         "or --camera looks elsewhere";
}

}  // namespace montecl
