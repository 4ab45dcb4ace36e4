// cmd_merge.cpp: `montecl merge a.exr b.exr ... -o out.exr`: combines AOV renders of one scene
// (channels R, G, B, samples, var.R/G/B and optional AOVs; see image/exr_layers.h) weighted by
// their per-pixel sample counts, with the variances combined exactly, and writes the result
// atomically. Inputs must carry a provenance (image/provenance.h) saying they show the same scene
// with the same settings and disjoint samples (--force skips the check); the output carries the union. Bad inputs (unreadable, wrong size, missing channels) are InputErrors naming the file.
// Merge does not denoise: the inputs' denoised.R/G/B layers (render --denoise) are dropped.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "cli/commands.h"
#include "cli/render_output.h"
#include "image/exr_layers.h"
#include "image/image_io.h"
#include "image/provenance.h"
#include "util/host_memory.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace montecl {
namespace {

// Removes the denoised.* planes: a mean of denoised parts is not the denoised merge, so merge
// combines only the estimates. Returns whether any was removed.
bool dropDenoised(LayeredImage& img) {
  bool dropped = false;
  for (std::size_t c = img.channels.size(); c-- > 0;)
    if (img.channels[c].rfind("denoised.", 0) == 0) {
      img.channels.erase(img.channels.begin() + std::ptrdiff_t(c));
      img.planes.erase(img.planes.begin() + std::ptrdiff_t(c));
      dropped = true;
    }
  return dropped;
}

struct MergeArgs {
  std::vector<std::string> inputs;
  std::string output;
  bool quiet = false, force = false;
};

// A NaN or infinite value would pass into the merged mean and variance of its pixel unnoticed.
void checkFinite(const LayeredImage& image, const std::string& path) {
  for (std::size_t c = 0; c < image.planes.size(); ++c)
    for (std::size_t p = 0; p < image.planes[c].size(); ++p)
      if (!std::isfinite(image.planes[c][p]))
        throwInputError(path, "",
                        "pixel (" + std::to_string(p % std::size_t(image.width)) + ", " +
                            std::to_string(p / std::size_t(image.width)) + ") channel '" + image.channels[c] +
                            "' is not finite");
}

// A pixel's sample count is a whole number a render can reach: a hand-edited -1, 2.5 or 1e30
// weighted its pixel's mean and variance by nonsense (a negative count was taken as 0).
void checkSampleCounts(const LayeredImage& image, const std::string& path) {
  const std::vector<float>* samples = image.find(channel::kSamples);
  if (!samples) return;
  constexpr double kMax = 9007199254740992.0;  // 2^53: past it a double no longer counts each sample
  for (std::size_t p = 0; p < samples->size(); ++p) {
    const double n = (*samples)[p];
    if (n >= 0.0 && n <= kMax && n == std::floor(n)) continue;
    char value[32];
    std::snprintf(value, sizeof value, "%g", n);
    throwInputError(path, "",
                    "pixel (" + std::to_string(p % std::size_t(image.width)) + ", " +
                        std::to_string(p / std::size_t(image.width)) + ") channel 'samples' is " + value +
                        ": a sample count is a whole number in [0, 2^53]");
  }
}

int runMerge(const MergeArgs& a) {
  checkOutputPath(a.output);
  std::string ext = std::filesystem::path(a.output).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".exr") throwInputError(a.output, "", "merge writes OpenEXR only (use .exr)");
  checkWritableTarget(a.output);
  for (const std::string& path : a.inputs)
    if (sameFile(a.output, path))
      throwInputError(a.output, "", "the output is an input of the merge ('" + path + "'): refusing to overwrite it");
  std::vector<LayeredImage> images;
  // Each input's share of the merged output (4 bytes per value) beyond its own decode.
  const ImageSizeCheck fits = [](int w, int h, int c) { return decodeMemoryRefusal(w, h, c, std::uint64_t(c) * 4); };
  bool dropped = false;
  for (const std::string& path : a.inputs) {
    images.push_back(readLayeredImage(path, fits));
    checkFinite(images.back(), path);
    checkSampleCounts(images.back(), path);
    dropped = dropDenoised(images.back()) || dropped;
  }
  if (dropped && !a.quiet)
    std::cerr << "montecl: note: merge does not denoise: the inputs' denoised.R/G/B layers were left out\n";
  LayeredImage merged = mergeLayeredImages(images, a.inputs);  // sizes and channels first
  std::optional<Provenance> provenance = mergeProvenance(images, a.inputs, a.force);
  merged.attributes.clear();
  if (provenance) setProvenance(merged, *provenance);
  writeLayeredExr(a.output, merged);
  if (!a.quiet) {
    const std::vector<float>& n = *merged.find(channel::kSamples);
    auto [lo, hi] = std::minmax_element(n.begin(), n.end());
    std::cout << "wrote " << a.output << ": merged " << images.size() << " image" << (images.size() == 1 ? "" : "s")
              << ", " << merged.width << "x" << merged.height << ", " << merged.channels.size() << " channels, "
              << (n.empty() ? 0.0f : *lo) << ".." << (n.empty() ? 0.0f : *hi) << " samples per pixel\n";
  }
  return kExitOk;
}

}  // namespace

void addMergeCommand(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* cmd = app.add_subcommand("merge", "Merge AOV EXR renders of one scene, weighted by per-pixel sample counts");
  cmd->add_option("inputs", args->inputs, "Input .exr renders (channels R, G, B, samples, optional var.R/G/B, AOVs)")
      ->required();
  cmd->add_option("-o,--output", args->output, "Output .exr")->required();
  cmd->add_flag("-q,--quiet", args->quiet, "No summary line");
  cmd->add_flag("--force", args->force,
                "Merge even renders whose provenance (EXR header: scene hash, settings, seed and sample range) "
                "says they must not be merged, or that have none (older renders)");
  cmd->callback([args, &exitCode]() { exitCode = runMerge(*args); });
}

}  // namespace montecl
