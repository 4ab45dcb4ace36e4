// provenance.cpp: the montecl:* header attributes of a render and the merge rules over them.
#include "image/provenance.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <sstream>

#include "image/exr_layers.h"
#include "util/errors.h"

namespace montecl {
namespace {

constexpr const char* kVersion = "montecl:version";
constexpr const char* kScene = "montecl:scene";
constexpr const char* kSettings = "montecl:settings";
constexpr const char* kAdaptive = "montecl:adaptive";
constexpr const char* kSamples = "montecl:samples";
constexpr const char* kForce = " (--force merges anyway)";

bool parseUnsigned(const std::string& s, std::uint64_t max, std::uint64_t& out) {
  if (s.empty() || s.size() > 20 || s.find_first_not_of("0123456789") != std::string::npos) return false;
  errno = 0;
  unsigned long long v = std::strtoull(s.c_str(), nullptr, 10);
  if (errno != 0 || v > max) return false;
  out = v;
  return true;
}

std::string rangeText(const SampleRange& r) {
  return "samples " + std::to_string(r.first) + ".." + std::to_string(r.end - 1) + " of seed " + std::to_string(r.seed);
}

bool overlap(const SampleRange& a, const SampleRange& b) {
  return a.seed == b.seed && a.first < b.end && b.first < a.end;
}

std::string joinDistinct(const std::vector<std::string>& values, const char* sep) {
  std::vector<std::string> seen;
  for (const std::string& v : values)
    if (std::find(seen.begin(), seen.end(), v) == seen.end()) seen.push_back(v);
  std::string out;
  for (const std::string& v : seen) out += (out.empty() ? "" : sep) + v;
  return out;
}

}  // namespace

std::string formatSampleRanges(const std::vector<SampleRange>& ranges) {
  std::string out;
  for (const SampleRange& r : ranges)
    out += (out.empty() ? "" : ",") + std::to_string(r.seed) + ":" + std::to_string(r.first) + "-" + std::to_string(r.end);
  return out;
}

std::optional<std::vector<SampleRange>> parseSampleRanges(const std::string& text) {
  std::vector<SampleRange> out;
  if (text.empty() || text.back() == ',') return std::nullopt;
  std::stringstream in(text);
  std::string entry;
  while (std::getline(in, entry, ',')) {
    const std::size_t colon = entry.find(':'), dash = entry.find('-');
    if (colon == std::string::npos || dash == std::string::npos || dash < colon) return std::nullopt;
    std::uint64_t seed = 0, first = 0, end = 0;
    if (!parseUnsigned(entry.substr(0, colon), 0xffffffffull, seed) ||
        !parseUnsigned(entry.substr(colon + 1, dash - colon - 1), ~0ull, first) ||
        !parseUnsigned(entry.substr(dash + 1), ~0ull, end) || end <= first)
      return std::nullopt;
    out.push_back({std::uint32_t(seed), first, end});
  }
  if (out.empty()) return std::nullopt;
  return out;
}

void setProvenance(LayeredImage& image, const Provenance& p) {
  image.attributes[kVersion] = p.version;
  image.attributes[kScene] = p.scene;
  image.attributes[kSettings] = p.settings;
  image.attributes[kAdaptive] = p.adaptive;
  image.attributes[kSamples] = formatSampleRanges(p.samples);
}

std::optional<Provenance> readProvenance(const LayeredImage& image, const std::string& name) {
  auto get = [&](const char* key) -> const std::string* {
    auto it = image.attributes.find(key);
    return it == image.attributes.end() ? nullptr : &it->second;
  };
  const std::string *scene = get(kScene), *samples = get(kSamples);
  if (!scene || !samples) return std::nullopt;
  Provenance p;
  p.scene = *scene;
  if (const std::string* v = get(kVersion)) p.version = *v;
  if (const std::string* v = get(kSettings)) p.settings = *v;
  if (const std::string* v = get(kAdaptive)) p.adaptive = *v;
  std::optional<std::vector<SampleRange>> ranges = parseSampleRanges(*samples);
  if (!ranges) throwInputError(name, kSamples, "malformed sample ranges '" + samples->substr(0, 80) + "'");
  p.samples = std::move(*ranges);
  return p;
}

std::optional<Provenance> mergeProvenance(const std::vector<LayeredImage>& images,
                                          const std::vector<std::string>& names, bool force) {
  auto nameOf = [&](std::size_t i) { return i < names.size() ? names[i] : "input " + std::to_string(i + 1); };
  std::vector<std::optional<Provenance>> in;
  for (std::size_t i = 0; i < images.size(); ++i) {
    in.push_back(readProvenance(images[i], nameOf(i)));
    if (!in.back() && !force)
      throwInputError(nameOf(i), "", std::string("no montecl provenance in its header (rendered by an older montecl, "
                                                 "or not by montecl render): cannot check it shows the same scene "
                                                 "with other samples") + kForce);
  }
  for (std::size_t i = 1; i < in.size() && !force; ++i) {
    const Provenance &a = *in[0], &b = *in[i];
    if (b.scene != a.scene)
      throwInputError(nameOf(i), "", "another scene than " + nameOf(0) + " (scene hash " + b.scene + ", not " +
                                         a.scene + ")" + kForce);
    if (b.settings != a.settings)
      throwInputError(nameOf(i), "", "other settings than " + nameOf(0) + " (" + b.settings + "; " + nameOf(0) +
                                         ": " + a.settings + ")" + kForce);
  }
  for (std::size_t i = 0; i < in.size() && !force; ++i)
    for (std::size_t j = 0; j < i; ++j)
      for (const SampleRange& a : in[i]->samples)
        for (const SampleRange& b : in[j]->samples)
          if (overlap(a, b))
            throwInputError(nameOf(i), "", rangeText(a) + " overlap " + nameOf(j) + "'s " + rangeText(b) +
                                               " (the same samples twice)" + kForce);

  Provenance out;
  std::vector<std::string> versions, scenes, settings, adaptive;
  for (const std::optional<Provenance>& p : in) {
    if (!p) return std::nullopt;  // forced past an input of unknown origin: claim nothing
    versions.push_back(p->version);
    scenes.push_back(p->scene);
    settings.push_back(p->settings);
    adaptive.push_back(p->adaptive);
    out.samples.insert(out.samples.end(), p->samples.begin(), p->samples.end());
  }
  out.version = joinDistinct(versions, ", ");
  out.scene = joinDistinct(scenes, " | ");
  out.settings = joinDistinct(settings, " | ");
  out.adaptive = joinDistinct(adaptive, " | ");
  std::sort(out.samples.begin(), out.samples.end(), [](const SampleRange& a, const SampleRange& b) {
    return a.seed != b.seed ? a.seed < b.seed : a.first != b.first ? a.first < b.first : a.end < b.end;
  });
  std::vector<SampleRange> joined;
  for (const SampleRange& r : out.samples) {
    if (!joined.empty() && joined.back().seed == r.seed && joined.back().end == r.first)
      joined.back().end = r.end;
    else
      joined.push_back(r);
  }
  out.samples = std::move(joined);
  return out;
}

}  // namespace montecl
