// pbrt_options.h: pbrt-v4's rendering options (Film, Sampler, Integrator, PixelFilter) as
// montecl's image size and render settings. Reads the directives' parameters; writes width,
// height and RenderSettings; what montecl lacks is one warning naming the directive's file:line.
#pragma once
#include <string>
#include <vector>

#include "scene/pbrt_params.h"
#include "scene/render_settings.h"

namespace montecl {

// Film: xresolution, yresolution (pbrt's defaults 1280 x 720 when absent).
void pbrtFilm(const std::string& type, const PbrtParams& params, int& width, int& height,
              std::vector<std::string>& warnings);
// Sampler: pixelsamples (stratified: xsamples x ysamples) as spp, the sampler kind, the seed.
void pbrtSampler(const std::string& type, const PbrtParams& params, RenderSettings& render,
                 std::vector<std::string>& warnings);
// Integrator: path / volpath (others warned) with maxdepth converted, or ambientocclusion.
void pbrtIntegrator(const std::string& type, const PbrtParams& params, RenderSettings& render,
                    std::vector<std::string>& warnings);
// PixelFilter: box, triangle, gaussian, mitchell, sinc (lanczos) into render.filter; others warned.
void pbrtPixelFilter(const std::string& type, const PbrtParams& params, RenderSettings& r,
                     std::vector<std::string>& warnings);

}  // namespace montecl
