// render_output.cpp: the output side of `montecl render` (see render_output.h).
#include "cli/render_output.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "image/oidn_api.h"
#include "image/oidn_denoiser.h"
#include "render/checkpoint.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace montecl {
namespace {

// Shortest decimal that reads back as the same float ("0.3", not "0.300000012").
std::string shortFloat(float v) {
  char buf[32];
  for (int precision = 6; precision <= 9; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, double(v));
    if (std::strtof(buf, nullptr) == v) break;
  }
  return buf;
}

std::string vec3Json(const glm::vec3& v) {
  return "[" + shortFloat(v.x) + ", " + shortFloat(v.y) + ", " + shortFloat(v.z) + "]";
}

}  // namespace

bool sameFile(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::equivalent(a, b, ec) && !ec) return true;
  const fs::path pa = fs::weakly_canonical(fs::absolute(a), ec);
  if (ec) return false;
  const fs::path pb = fs::weakly_canonical(fs::absolute(b), ec);
  return !ec && pa == pb;
}

namespace {

// The absolute, normal path in lower case: two paths equal so name one file for the loaders, which
// open a file named in another case of its letters (load_util.h findIgnoringCase).
std::string caseFolded(const std::string& path) {
  std::error_code ec;
  std::string p = std::filesystem::weakly_canonical(std::filesystem::absolute(path), ec).string();
  if (ec) p = std::filesystem::absolute(path).lexically_normal().string();
  for (char& c : p) c = char(std::tolower(static_cast<unsigned char>(c)));
  return p;
}

}  // namespace

// Refuses an output that is one of the files the render reads (the scene, an OBJ, an MTL, a
// texture), in any case of its letters: on a case-insensitive file system `-o Wood.PNG` replaces
// Wood.png, and on Linux the model would then read the render as its texture Wood.PNG.
void checkOutputIsNoInput(const std::string& output, const Scene& scene) {
  const std::string folded = caseFolded(output);
  for (const std::string& in : scene.inputFiles) {
    std::error_code ec;
    if ((std::filesystem::equivalent(output, in, ec) && !ec) || caseFolded(in) == folded)
      throwInputError(output, "", "the output is an input of the render ('" + in + "'): refusing to overwrite it");
  }
}

void checkJobFiles(const std::string& checkpoint, const std::string& resume, const std::string& output,
                   const Scene& scene) {
  if (!resume.empty() && sameFile(resume, output))
    throwInputError(output, "", "the output is the --resume checkpoint: refusing to overwrite it");
  if (checkpoint.empty()) return;
  if (sameFile(checkpoint, output))
    throwInputError(checkpoint, "--checkpoint", "is also the output image (-o): give the checkpoint its own file");
  for (const std::string& in : scene.inputFiles)
    if (sameFile(checkpoint, in))
      throwInputError(checkpoint, "--checkpoint", "is an input of the render ('" + in + "'): refusing to overwrite it");
  std::error_code ec;
  const auto st = std::filesystem::status(checkpoint, ec);
  if (std::filesystem::exists(st) && !std::filesystem::is_directory(st) &&
      !(std::filesystem::is_regular_file(st) && isCheckpointFile(checkpoint)))
    throwInputError(checkpoint, "--checkpoint", "exists and is not a montecl checkpoint: refusing to overwrite it");
  checkWritableTarget(checkpoint, "the checkpoint");
}

bool isExr(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".exr";
}

// The number of pixels with a NaN or infinite value in any plane (values that overflowed a float).
std::size_t nonFinitePixels(const LayeredImage& img) {
  std::size_t bad = 0;
  for (std::size_t p = 0; p < img.pixelCount(); ++p) {
    bool finite = true;
    for (const std::vector<float>& plane : img.planes) finite = finite && std::isfinite(plane[p]);
    bad += !finite;
  }
  return bad;
}

// The EXR layers: R, G, B, samples, var.R/G/B, and the AOVs asked for, averaged over samples:
// albedo.R/G/B, N.X/Y/Z (facing geometric normal), Z (distance along the camera ray),
// emission.R/G/B (radiance emitted by what the camera ray sees directly).
LayeredImage renderLayers(Film& film, const std::vector<std::string>& aovs) {
  LayeredImage img = takeLayersFromFilm(film);
  auto wants = [&](const char* name) {
    return std::find(aovs.begin(), aovs.end(), name) != aovs.end() ||
           std::find(aovs.begin(), aovs.end(), "all") != aovs.end();
  };
  const std::size_t pixels = film.pixelCount();
  auto plane = [&](int vec, int comp) {
    std::vector<float> out(pixels, 0.0f);
    for (std::size_t p = 0; p < pixels; ++p)
      if (double(film.count[p]) > 0) out[p] = film.aovSum[MCL_AOV_VECTORS * p + vec][comp] / double(film.count[p]);
    return out;
  };
  if (wants("albedo"))
    for (int c = 0; c < 3; ++c) img.set(std::string("albedo.") + "RGB"[c], plane(0, c));
  if (wants("normal"))
    for (int c = 0; c < 3; ++c) img.set(std::string("N.") + "XYZ"[c], plane(1, c));
  if (wants("depth")) img.set("Z", plane(0, 3));
  if (wants("emission"))
    for (int c = 0; c < 3; ++c) img.set(std::string("emission.") + "RGB"[c], plane(2, c));
  std::vector<glm::vec4>().swap(film.aovSum);
  return img;
}

namespace {

int oidnQuality(DenoiseQuality q) {
  switch (q) {
    case DenoiseQuality::Fast: return oidn::kQualityFast;
    case DenoiseQuality::Balanced: return oidn::kQualityBalanced;
    case DenoiseQuality::High: return oidn::kQualityHigh;
  }
  return oidn::kQualityHigh;
}

}  // namespace

// The guides are the film's own AOV averages (as noisy as the color: no cleanAux), so the
// denoiser sees the same samples the estimate does. The emission seen directly (the emission AOV's
// mean) is taken out of the color before the filter and added back after it: it carries no noise
// from light transport (only the pixel footprint's), and a bright emitter's exact pixels came out
// of the filter with errors of the order of its radiance at its corners and edges. The albedo guide
// on an emitter stays its BSDF's albedo: what is left of its color is the light it reflects.
std::vector<float> denoiseFilm(const Film& film, DenoiseQuality quality, bool quiet, double& seconds) {
  const std::size_t pixels = film.pixelCount();
  std::vector<float> albedo(3 * pixels, 0.0f), normal(3 * pixels, 0.0f), emission(3 * pixels, 0.0f);
  std::vector<float> rest = film.meanRgb();
  if (film.aovSum.size() == MCL_AOV_VECTORS * pixels)
    for (std::size_t p = 0; p < pixels; ++p) {
      if (film.count[p] == 0) continue;
      const double n = double(film.count[p]);
      for (int c = 0; c < 3; ++c) {
        albedo[3 * p + c] = float(film.aovSum[MCL_AOV_VECTORS * p][c] / n);
        normal[3 * p + c] = float(film.aovSum[MCL_AOV_VECTORS * p + 1][c] / n);
        emission[3 * p + c] = float(film.aovSum[MCL_AOV_VECTORS * p + 2][c] / n);
        // The rest in double from the film's float-float mean; never below 0 (OIDN's HDR range).
        rest[3 * p + c] = float(std::max(0.0, film.meanOf(p, c) - film.aovSum[MCL_AOV_VECTORS * p + 2][c] / n));
      }
    }
  if (!quiet)
    std::cerr << "denoising " << film.width << "x" << film.height << " (Open Image Denoise, RT filter, quality "
              << choiceName(denoiseQualityNames(), quality) << ")\n";
  const auto start = std::chrono::steady_clock::now();
  std::vector<float> out = oidnDenoise(film.width, film.height, rest, albedo, normal, oidnQuality(quality));
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (std::size_t i = 0; i < out.size(); ++i) out[i] += emission[i];
  return out;
}

void addRgbPlanes(LayeredImage& img, const std::string& prefix, const std::vector<float>& rgb) {
  for (int c = 0; c < 3; ++c) {
    std::vector<float> plane(img.pixelCount());
    for (std::size_t p = 0; p < plane.size(); ++p) plane[p] = rgb[3 * p + c];
    img.set(prefix + channel::kMean[c], std::move(plane));
  }
}

// The camera as a scene-file "camera" entry, to copy into a scene file (-v); the thin-lens keys
// only when they are set.
std::string cameraJson(const Camera& c) {
  std::string lens;
  if (c.apertureRadius > 0.0f) lens += ", \"aperture_radius\": " + shortFloat(c.apertureRadius);
  if (c.focusDistance > 0.0f) lens += ", \"focus_distance\": " + shortFloat(c.focusDistance);
  return "\"camera\": {\"position\": " + vec3Json(c.position) + ", \"target\": " + vec3Json(c.target) +
         ", \"up\": " + vec3Json(c.up) + ", \"fov_y\": " + shortFloat(c.fovY) + ", \"width\": " +
         std::to_string(c.width) + ", \"height\": " + std::to_string(c.height) + lens + "}";
}

// The default output: <stem>.png in the current folder, named after the scene's folder when the
// file is scene.json (every shared scene is). An existing file is never replaced without
// --overwrite: the first free <name>-N.png is used instead, and `note` says so.
std::string defaultOutput(const std::string& scenePath, bool overwrite, std::string& note, const std::string& suffix) {
  namespace fs = std::filesystem;
  fs::path scene(scenePath);
  std::string stem = scene.stem().string();
  if (scene.filename() == "scene.json") {
    std::string folder = fs::absolute(scene).lexically_normal().parent_path().filename().string();
    if (!folder.empty()) stem = folder;
  }
  stem += suffix;
  const std::string name = stem + ".png";
  std::error_code ec;
  if (overwrite || !fs::exists(fs::symlink_status(name, ec))) return name;
  for (int n = 1;; ++n) {
    std::string numbered = stem + "-" + std::to_string(n) + ".png";
    if (!fs::exists(fs::symlink_status(numbered, ec))) {
      note = " (" + name + " exists and was kept; --overwrite replaces it)";
      return numbered;
    }
  }
}

}  // namespace montecl
