// pbrt_options.cpp: pbrt-v4's rendering options (pbrt_options.h): reads the Film, Sampler,
// Integrator and PixelFilter directives' parameters, writes the image size and montecl's
// RenderSettings.
#include "scene/pbrt_options.h"

#include <algorithm>

#include "scene/load_util.h"

namespace montecl {
namespace {

void warnAt(const PbrtParams& p, std::vector<std::string>& warnings, const std::string& text) {
  warnings.push_back(p.loc.str() + ": " + text);
}

}  // namespace

void pbrtFilm(const std::string& type, const PbrtParams& p, int& width, int& height, std::vector<std::string>& warnings) {
  if (type != "rgb" && type != "gbuffer" && type != "spectral")
    warnAt(p, warnings, "Film \"" + oneLine(type, 40) + "\" not known; read as \"rgb\"");
  width = p.getInt("xresolution", 1280);
  height = p.getInt("yresolution", 720);
  if (width < 1 || width > kMaxImageSide || height < 1 || height > kMaxImageSide)
    pbrtFail(p.loc, "Film: the resolution must be 1 to " + std::to_string(kMaxImageSide) + " pixels a side, got " +
                        std::to_string(width) + " x " + std::to_string(height));
  p.ignore("filename");  // the command line's -o names the output
  if (type != "rgb") for (const PbrtParam& q : p.list) q.used = true;
  for (const char* quiet : {"sensor", "iso", "whitebalance", "exposuretime", "savefp16", "maxcomponentvalue", "diagonal"})
    p.ignore(quiet);  // pbrt's defaults leave RGB radiance as it is (imaging ratio 1)
  if (p.find("cropwindow") || p.find("pixelbounds")) warnAt(p, warnings, "Film: cropping is not read by montecl; the whole image is rendered");
  p.reportUnused("Film", warnings);
}

void pbrtSampler(const std::string& type, const PbrtParams& p, RenderSettings& r, std::vector<std::string>& warnings) {
  long long spp = p.getInt("pixelsamples", 16);
  if (type == "stratified") {
    const long long xs = p.getInt("xsamples", 4), ys = p.getInt("ysamples", 4);
    p.ignore("jitter");
    spp = xs < 1 || ys < 1 ? 0 : xs * ys;
  }
  if (spp < 1 || spp > 2147483647LL)
    pbrtFail(p.loc, "Sampler: the number of samples per pixel must be 1 to 2147483647, got " + std::to_string(spp));
  r.spp = int(spp);
  r.sampler = type == "independent" ? Sampler::Independent : Sampler::Sobol;
  const int seed = p.getInt("seed", 0);
  if (seed < 0) pbrtFail(p.find("seed")->loc, "Sampler: 'seed' must be >= 0");
  r.seed = std::uint32_t(seed);
  p.ignore("randomization");
  p.reportUnused("Sampler \"" + oneLine(type, 40) + "\"", warnings);
}

void pbrtIntegrator(const std::string& type, const PbrtParams& p, RenderSettings& r, std::vector<std::string>& warnings) {
  // pbrt's maxdepth counts bounces (0: emitters seen, 1: direct lighting); montecl's max_depth
  // is Mitsuba's, counting path segments (1: emitters seen, 2: direct): one more.
  const int depth = p.getInt("maxdepth", 5);
  if (depth < 0) pbrtFail(p.loc, "Integrator: 'maxdepth' must be >= 0");
  r.integrator = Integrator::Path;
  r.maxDepth = depth >= 1000000 ? -1 : depth + 1;
  p.ignore("regularize");
  p.ignore("lightsampler");
  if (type == "ambientocclusion") {
    r.integrator = Integrator::Ao;
    r.aoSampling = p.getBool("cossample", true) ? AoSampling::Cosine : AoSampling::Uniform;
    const double dist = p.getFloat("maxdistance", 1e30);
    if (!(dist > 0.0)) pbrtFail(p.loc, "Integrator: 'maxdistance' must be > 0");
    r.aoDistance = float(std::min(dist, 1e30));
  } else if (type != "path" && type != "volpath") {
    warnAt(p, warnings, "Integrator \"" + oneLine(type, 40) + "\": montecl renders it with its path tracer (same maxdepth)");
    for (const PbrtParam& q : p.list) q.used = true;
  }
  p.reportUnused("Integrator \"" + oneLine(type, 40) + "\"", warnings);
}

// pbrt-v4's filters by their names ("sinc" is its windowed Lanczos), their radius and parameters;
// montecl's filter has one radius: different x and y radii take the larger, warned.
void pbrtPixelFilter(const std::string& type, const PbrtParams& p, RenderSettings& r, std::vector<std::string>& warnings) {
  const std::string name = type == "sinc" ? "lanczos" : type;
  PixelFilter f;
  if (!defaultFilter(name, f)) {
    warnAt(p, warnings, "PixelFilter \"" + oneLine(type, 40) + "\": unknown to montecl; a box of radius 0.5 is used");
    for (const PbrtParam& q : p.list) q.used = true;
    return;
  }
  const double xr = p.getFloat("xradius", f.radius), yr = p.getFloat("yradius", f.radius);
  if (xr != yr) warnAt(p, warnings, "PixelFilter: montecl's filters have one radius; the larger of xradius and yradius is used");
  std::vector<std::pair<const char*, double>> params = {{"radius", std::max(xr, yr)}};
  if (f.type == FilterType::Gaussian) params.push_back({"sigma", p.getFloat("sigma", f.sigma)});
  if (f.type == FilterType::Mitchell) params.push_back({"b", p.getFloat("B", f.b)}), params.push_back({"c", p.getFloat("C", f.c)});
  if (f.type == FilterType::Lanczos) params.push_back({"tau", p.getFloat("tau", f.tau)});
  std::string problem;
  for (const auto& q : params)
    if (!setFilterParam(f, q.first, float(q.second), &problem))
      pbrtFail(p.loc, "PixelFilter \"" + oneLine(type, 40) + "\": " + problem);
  r.filter = f;
  p.reportUnused("PixelFilter \"" + oneLine(type, 40) + "\"", warnings);
}

}  // namespace montecl
