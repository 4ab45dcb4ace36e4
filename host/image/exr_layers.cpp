// exr_layers.cpp: named-channel float EXR output (OpenEXR, exr_writer.cpp) and input (image_read.h), the film -> AOV planes
// conversion, and the sample-count-weighted merge of renders (parallel variance formula).
#include "image/exr_layers.h"
#include "image/exr_writer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>

#include "image/film.h"
#include "image/image_read.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace montecl {
namespace {

bool isMeanChannel(const std::string& name, int& c) {
  for (c = 0; c < 3; ++c)
    if (name == channel::kMean[c]) return true;
  return false;
}

bool isVarianceChannel(const std::string& name) {
  for (const char* v : channel::kVariance)
    if (name == v) return true;
  return false;
}

// split<k>.n (a sub-sequence's sample count): the prefix split<k>.
bool isSplitCountChannel(const std::string& name, std::string& prefix) {
  if (name.rfind("split", 0) != 0 || name.size() < 8 || name.compare(name.size() - 2, 2, ".n") != 0) return false;
  prefix = name.substr(0, name.size() - 2);
  return true;
}

// split<k>.R/G/B: the prefix split<k>.
bool isSplitMeanChannel(const std::string& name, std::string& prefix) {
  if (name.rfind("split", 0) != 0 || name.size() < 8 || name[name.size() - 2] != '.') return false;
  const char c = name.back();
  if (c != 'R' && c != 'G' && c != 'B') return false;
  prefix = name.substr(0, name.size() - 2);
  return true;
}

bool isErrorChannel(const std::string& name) {
  for (const char* e : channel::kMeanError)
    if (name == e) return true;
  return false;
}

// err.R/G/B from the split<k> planes (Film::meanVariance's formula), where the image has them.
void setMeanErrorFromSplits(LayeredImage& image) {
  std::vector<const std::vector<float>*> counts, means[3];
  for (std::size_t k = 0;; ++k) {
    const std::string prefix = channel::splitPrefix(k);
    const std::vector<float>* n = image.find(prefix + ".n");
    if (!n) break;
    counts.push_back(n);
    for (int c = 0; c < 3; ++c) means[c].push_back(image.find(prefix + "." + channel::kMean[c]));
  }
  if (counts.size() < 2) return;
  const std::size_t pixels = image.pixelCount(), k = counts.size();
  std::vector<double> ns(k), ms(k);
  for (int c = 0; c < 3; ++c) {
    std::vector<float> err(pixels, 0.0f);
    for (std::size_t p = 0; p < pixels; ++p) {
      for (std::size_t i = 0; i < k; ++i) ns[i] = (*counts[i])[p], ms[i] = means[c][i] ? (*means[c][i])[p] : 0.0;
      const double v = splitMeanVariance(ns.data(), ms.data(), k);
      err[p] = std::isfinite(v) ? float(v) : 0.0f;
    }
    image.set(channel::kMeanError[c], std::move(err));
  }
}

}  // namespace

std::string channel::splitPrefix(std::size_t k) { return "split" + std::to_string(k); }

const std::vector<float>* LayeredImage::find(const std::string& name) const {
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (channels[c] == name) return &planes[c];
  return nullptr;
}

std::vector<float>* LayeredImage::find(const std::string& name) {
  return const_cast<std::vector<float>*>(static_cast<const LayeredImage*>(this)->find(name));
}

void LayeredImage::set(const std::string& name, std::vector<float> plane) {
  if (std::vector<float>* p = find(name)) {
    *p = std::move(plane);
    return;
  }
  channels.push_back(name);
  planes.push_back(std::move(plane));
}

void writeLayeredExr(const std::string& path, const LayeredImage& image) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  if (ext != ".exr") throwInputError(path, "", "multi-channel images must be written as .exr");
  if (image.channels.empty() || image.channels.size() != image.planes.size())
    throw RuntimeError("cannot write " + path + ": no channels, or channel names and planes differ in number");
  const std::size_t count = image.pixelCount(), nch = image.channels.size();
  for (std::size_t c = 0; c < nch; ++c)
    if (image.planes[c].size() != count)
      throw RuntimeError("cannot write " + path + ": channel '" + image.channels[c] + "' has " +
                         std::to_string(image.planes[c].size()) + " values, not " + std::to_string(count));
  writeAtomically(path, [&](const std::string& tmp) { writeExrFile(tmp, path, image); });
}

LayeredImage readLayeredImage(const std::string& path, const ImageSizeCheck& check) {
  if (!std::filesystem::exists(path)) throwInputError(path, "", "cannot read image: no such file");
  return readImageFile(path, check);
}

std::string badPixelValue(const std::vector<const std::vector<float>*>& planes, int width, float maxValue) {
  const std::size_t count = planes.empty() ? 0 : planes[0]->size();
  for (std::size_t i = 0; i < count; ++i)
    for (const std::vector<float>* plane : planes) {
      const float v = (*plane)[i];
      if (std::isfinite(v) && v >= 0.0f && v <= maxValue) continue;
      const std::string where =
          "pixel (" + std::to_string(i % std::size_t(width)) + ", " + std::to_string(i / std::size_t(width)) + ")";
      if (!(std::isfinite(v) && v >= 0.0f)) return where + " is negative or not finite";
      char buf[64];
      std::snprintf(buf, sizeof buf, " is %g, over %g", double(v), double(maxValue));
      return where + buf;
    }
  return "";
}

// Each accumulator is freed once its planes are made, so the film and the planes are never both
// whole (an output file's peak memory).
LayeredImage takeLayersFromFilm(Film& film) {
  LayeredImage image;
  image.width = film.width;
  image.height = film.height;
  const std::size_t count = film.pixelCount();
  std::vector<float> mean[3], var[3], samples(count, 0.0f);
  for (int c = 0; c < 3; ++c) {
    mean[c].assign(count, 0.0f);
    var[c].assign(count, 0.0f);
  }
  for (std::size_t p = 0; p < count; ++p) {
    double n = double(film.count[p]);
    samples[p] = float(n);
    if (n <= 0.0) continue;
    for (int c = 0; c < 3; ++c) {
      mean[c][p] = film.mean[p][c];
      var[c][p] = float(film.variance(p, c));
    }
  }
  for (int c = 0; c < 3; ++c) image.set(channel::kMean[c], std::move(mean[c]));
  image.set(channel::kSamples, std::move(samples));
  for (int c = 0; c < 3; ++c) image.set(channel::kVariance[c], std::move(var[c]));
  for (std::vector<glm::vec4>* v : {&film.mean, &film.meanLo, &film.m2, &film.m2Lo})
    std::vector<glm::vec4>().swap(*v);
  // The sobol sampler's sub-sequences (Film::split): each one's mean and count, and the error of
  // the mean estimated from their spread; renders without them keep exactly the layers above.
  const std::size_t splits = film.splits();
  if (splits > 1) {
    for (std::size_t k = 0; k < splits; ++k) {
      std::vector<float> sub[3], n(count, 0.0f);
      for (int c = 0; c < 3; ++c) sub[c].assign(count, 0.0f);
      for (std::size_t p = 0; p < count; ++p) {
        n[p] = float(film.splitCount(p, k));
        for (int c = 0; c < 3; ++c) sub[c][p] = film.split[splits * p + k][c];
      }
      const std::string prefix = channel::splitPrefix(k);
      for (int c = 0; c < 3; ++c) image.set(prefix + "." + channel::kMean[c], std::move(sub[c]));
      image.set(prefix + ".n", std::move(n));
    }
    for (int c = 0; c < 3; ++c) {
      std::vector<float> err(count, 0.0f);
      for (std::size_t p = 0; p < count; ++p) {
        const double v = film.count[p] > 0 ? film.meanVariance(p, c) : 0.0;
        err[p] = std::isfinite(v) ? float(v) : 0.0f;
      }
      image.set(channel::kMeanError[c], std::move(err));
    }
  }
  std::vector<glm::vec4>().swap(film.split);
  return image;
}

SampleStats combineStats(const std::vector<SampleStats>& parts) {
  SampleStats out;
  double weighted = 0.0;
  for (const SampleStats& s : parts) {
    if (s.n <= 0.0) continue;
    out.n += s.n;
    weighted += s.n * s.mean;
  }
  if (out.n <= 0.0) return out;
  out.mean = weighted / out.n;
  double m2 = 0.0;
  for (const SampleStats& s : parts) {
    if (s.n <= 0.0) continue;
    double d = s.mean - out.mean;
    m2 += (s.n - 1.0) * s.variance + s.n * d * d;
  }
  out.variance = out.n > 1.0 ? std::max(0.0, m2 / (out.n - 1.0)) : 0.0;
  return out;
}

LayeredImage mergeLayeredImages(const std::vector<LayeredImage>& images, const std::vector<std::string>& names) {
  if (images.empty()) throw InputError("merge: no input images");
  auto nameOf = [&](std::size_t i) { return i < names.size() ? names[i] : "input " + std::to_string(i + 1); };
  const LayeredImage& first = images.front();
  std::set<std::string> firstSet(first.channels.begin(), first.channels.end());
  for (std::size_t i = 0; i < images.size(); ++i) {
    const LayeredImage& im = images[i];
    for (const char* required : {channel::kMean[0], channel::kMean[1], channel::kMean[2], channel::kSamples})
      if (!im.find(required))
        throwInputError(nameOf(i), "", std::string("no '") + required + "' channel (not a montecl AOV render?)");
    if (im.width != first.width || im.height != first.height)
      throwInputError(nameOf(i), "", "size " + std::to_string(im.width) + "x" + std::to_string(im.height) +
                                         " differs from " + nameOf(0) + " (" + std::to_string(first.width) + "x" +
                                         std::to_string(first.height) + ")");
    for (const std::string& ch : first.channels)
      if (!im.find(ch)) throwInputError(nameOf(i), "", "no '" + ch + "' channel (" + nameOf(0) + " has one)");
    for (const std::string& ch : im.channels)
      if (!firstSet.count(ch))
        throwInputError(nameOf(i), "", "channel '" + ch + "' is not in " + nameOf(0));
  }
  if (images.size() == 1) return first;

  const std::size_t count = first.pixelCount(), k = images.size();
  std::vector<const std::vector<float>*> samples(k);
  for (std::size_t i = 0; i < k; ++i) samples[i] = images[i].find(channel::kSamples);

  LayeredImage out;
  out.width = first.width;
  out.height = first.height;
  out.channels = first.channels;
  out.planes.assign(first.channels.size(), std::vector<float>(count, 0.0f));
  auto outPlane = [&](const std::string& name) { return out.find(name); };

  std::vector<SampleStats> parts(k);
  for (std::size_t ci = 0; ci < first.channels.size(); ++ci) {
    const std::string& name = first.channels[ci];
    std::vector<float>& dst = out.planes[ci];
    int mc = 0;
    if (name == channel::kSamples) {
      for (std::size_t p = 0; p < count; ++p) {
        double n = 0.0;
        for (std::size_t i = 0; i < k; ++i) n += std::max(0.0f, (*samples[i])[p]);
        dst[p] = float(n);
      }
    } else if (isMeanChannel(name, mc)) {
      const std::string varName = channel::kVariance[mc];
      bool withVar = first.find(varName) != nullptr;
      std::vector<float>* varDst = withVar ? outPlane(varName) : nullptr;
      std::vector<const std::vector<float>*> means(k), vars(k, nullptr);
      for (std::size_t i = 0; i < k; ++i) {
        means[i] = images[i].find(name);
        if (withVar) vars[i] = images[i].find(varName);
      }
      for (std::size_t p = 0; p < count; ++p) {
        for (std::size_t i = 0; i < k; ++i) {
          parts[i].n = std::max(0.0f, (*samples[i])[p]);
          parts[i].mean = (*means[i])[p];
          parts[i].variance = withVar ? (*vars[i])[p] : 0.0;
        }
        SampleStats s = combineStats(parts);
        dst[p] = float(s.mean);
        if (varDst) (*varDst)[p] = float(s.variance);
      }
    } else if (isVarianceChannel(name) || isErrorChannel(name)) {
      continue;  // written with its mean channel; err.* from the merged sub-sequences below
    } else if (std::string prefix; isSplitCountChannel(name, prefix)) {
      for (std::size_t p = 0; p < count; ++p) {
        double n = 0.0;
        for (std::size_t i = 0; i < k; ++i) n += std::max(0.0f, (*images[i].find(name))[p]);
        dst[p] = float(n);
      }
    } else if (isSplitMeanChannel(name, prefix) && first.find(prefix + ".n")) {
      // A sub-sequence's mean, weighted by its own counts.
      for (std::size_t p = 0; p < count; ++p) {
        double n = 0.0, sum = 0.0;
        for (std::size_t i = 0; i < k; ++i) {
          const double ni = std::max(0.0f, (*images[i].find(prefix + ".n"))[p]);
          n += ni;
          sum += ni * (*images[i].find(name))[p];
        }
        dst[p] = float(n > 0.0 ? sum / n : 0.0);
      }
    } else {
      std::vector<const std::vector<float>*> src(k);
      for (std::size_t i = 0; i < k; ++i) src[i] = images[i].find(name);
      for (std::size_t p = 0; p < count; ++p) {
        double n = 0.0, sum = 0.0, plain = 0.0;
        for (std::size_t i = 0; i < k; ++i) {
          double ni = std::max(0.0f, (*samples[i])[p]), v = (*src[i])[p];
          n += ni;
          sum += ni * v;
          plain += v;
        }
        dst[p] = float(n > 0.0 ? sum / n : plain / double(k));
      }
    }
  }
  setMeanErrorFromSplits(out);
  return out;
}

}  // namespace montecl
