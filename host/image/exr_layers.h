// exr_layers.h: multi-channel float EXR images with named channels (OpenEXR layer convention
// "layer.channel"), written from named planes with OpenEXR (image/exr_writer.cpp) and read back
// into them with OpenEXR too (image/exr_read.h, in OpenImageIO's channel order); the AOV
// layout of montecl's renders; and the per-pixel merge of several renders of one scene weighted
// by their sample counts (exact parallel-variance combination).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "image/oiio_loader.h"

namespace montecl {

struct Film;

// Channel names of montecl's AOV EXR (R, G, B and samples are required by `montecl merge`).
//   R G B          mean radiance per pixel
//   samples        per-pixel sample count n
//   var.R var.G var.B   unbiased sample variance of ONE sample, s^2 = sum (x - mean)^2 / (n - 1)
//                       (0 where n < 2); the variance of the mean is var / n
//   albedo.R/G/B, N.X/Y/Z, Z, emission.R/G/B   optional AOVs (first-hit albedo, normal, depth,
//                       emitted radiance seen directly): averaged by n
// With the sobol sampler's K > 1 sub-sequences (render.sobol_splits) also:
//   split<k>.R/G/B split<k>.n   sub-sequence k's mean and sample count (k = 0 .. K-1)
//   err.R err.G err.B   the estimated squared standard error of the mean R G B, from the spread
//                       of the sub-means (Film::meanVariance; var / n overstates it under sobol)
namespace channel {
constexpr const char* kSamples = "samples";
inline const char* const kMean[3] = {"R", "G", "B"};
inline const char* const kVariance[3] = {"var.R", "var.G", "var.B"};
inline const char* const kMeanError[3] = {"err.R", "err.G", "err.B"};
std::string splitPrefix(std::size_t k);  // split<k>
}  // namespace channel

// width x height float planes, one per named channel, each width * height, row 0 at the top.
struct LayeredImage {
  int width = 0, height = 0;
  std::vector<std::string> channels;
  std::vector<std::vector<float>> planes;  // planes[c] belongs to channels[c]
  // String header attributes written with the image and read back (only names starting with
  // "montecl:" are read): the render's provenance (image/provenance.h).
  std::map<std::string, std::string> attributes;
  // What the file stored, as OpenImageIO names it ("uint8", "uint16", "half", "float", ...): set
  // by reads only (textures decode integer images as sRGB, float ones as linear).
  std::string pixelType;

  std::size_t pixelCount() const { return std::size_t(width) * std::size_t(height); }
  // The plane named name, or nullptr.
  const std::vector<float>* find(const std::string& name) const;
  std::vector<float>* find(const std::string& name);
  // Appends (or replaces) a plane; it must hold pixelCount() values.
  void set(const std::string& name, std::vector<float> plane);
};

// Writes every plane as a 32-bit float channel of an OpenEXR file, atomically (temporary + rename).
// Throws InputError when path does not end in .exr or a plane has the wrong size, RuntimeError
// when writing fails.
void writeLayeredExr(const std::string& path, const LayeredImage& image);

// Reads every channel of an image (image/image_read.h: PNG, JPEG, EXR and HDR by montecl's
// readers, any other format OpenImageIO reads; channel names as stored) as float planes. Throws InputError "<path>: cannot read image: ..." (one line) when it cannot be read or
// check (image/oiio_loader.h) refuses the size it declares.
LayeredImage readLayeredImage(const std::string& path, const ImageSizeCheck& check = {});

// The rule for pixels that become radiance or reflectance (environment maps, textures): the first
// pixel, in row order, whose value in one of planes (width pixels a row) is negative, not finite or
// over maxValue, as "pixel (x, y) is negative or not finite" / "pixel (x, y) is <v>, over <max>";
// "" when there is none.
std::string badPixelValue(const std::vector<const std::vector<float>*>& planes, int width, float maxValue);

// The renderer's AOV image from its film: R, G, B (mean), samples, var.R/G/B (unbiased s^2 of one
// sample from the sums, clamped at 0), and with sobol's sub-sequences split<k>.R/G/B/n and
// err.R/G/B. Add optional AOV planes with set() before writing. The film's accumulators (mean, M2,
// sub-sequences) are freed as their planes are made: afterwards it holds its size, sample counts
// and AOV sums only (an output file's peak memory: the film and its planes are never both whole).
LayeredImage takeLayersFromFilm(Film& film);

// --- merging -------------------------------------------------------------------------------
// Statistics of one pixel channel: sample count, mean and unbiased variance of one sample.
struct SampleStats {
  double n = 0.0, mean = 0.0, variance = 0.0;
};
// Exact combination of disjoint sample sets: n = sum n_i, mean = sum n_i m_i / n,
// M2 = sum [(n_i - 1) s_i^2 + n_i (m_i - mean)^2], s^2 = M2 / (n - 1) (0 when n < 2).
SampleStats combineStats(const std::vector<SampleStats>& parts);

// Merges renders of one scene: sizes must match and every input must have the first input's
// channels, including R, G, B and samples. Channels: samples summed; R/G/B combined with var.R/G/B
// by combineStats (means weighted by n without var.*); every other channel averaged weighted by n
// (plain average where the total n is 0). names[i] names images[i] in InputError messages
// ("<name>: <problem>"). One image is returned unchanged.
LayeredImage mergeLayeredImages(const std::vector<LayeredImage>& images, const std::vector<std::string>& names);

}  // namespace montecl
