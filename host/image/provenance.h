// provenance.h: what an EXR render was made of, kept in its header as string attributes, so that
// `montecl merge` can refuse renders that must not be combined:
//   montecl:version   montecl version(s) that rendered it ("0.14.0"; merged: the distinct ones, ", ")
//   montecl:scene     scene content hash (scene/scene_digest.h)
//   montecl:settings  integrator and its settings ("integrator=ao ao_sampling=cosine ...")
//   montecl:adaptive  "off" or "target_error=E min_spp=A max_spp=B" (recorded, not compared)
//   montecl:samples   sample ranges per seed, "seed:first-end" (end exclusive), comma-separated:
//                     "0:0-64" for --seed 0 --spp 64, "0:0-64,0:128-192,7:0-64" after merges.
//                     An adaptive render claims [first, first + max_spp); one stopped early (--time,
//                     a signal) claims all it was asked for: the check errs on refusing.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace montecl {

struct LayeredImage;

struct SampleRange {
  std::uint32_t seed = 0;
  std::uint64_t first = 0, end = 0;  // sample indices [first, end)
};

struct Provenance {
  std::string version, scene, settings, adaptive;
  std::vector<SampleRange> samples;
};

// "0:0-64,0:128-192" and back. parseSampleRanges returns nullopt on any malformed entry.
std::string formatSampleRanges(const std::vector<SampleRange>& ranges);
std::optional<std::vector<SampleRange>> parseSampleRanges(const std::string& text);

// Writes the montecl:* attributes into image.attributes.
void setProvenance(LayeredImage& image, const Provenance& p);

// The provenance in image.attributes; nullopt when it has none (no montecl:scene or
// montecl:samples: an older render, or not a montecl render). Throws InputError "<name>: ..."
// when the attributes are present but malformed.
std::optional<Provenance> readProvenance(const LayeredImage& image, const std::string& name);

// Checks that renders may be merged: every one has a provenance; the same scene and settings; no
// two sample ranges of one seed overlap (the same samples counted twice). Throws InputError, one
// line naming the file and what differs, ending in "(--force merges anyway)". With force nothing
// is refused. Returns the union provenance for the merged image: ranges sorted and touching ones
// of a seed joined; differing values (forced) joined with " | "; nullopt when some input had none.
std::optional<Provenance> mergeProvenance(const std::vector<LayeredImage>& images,
                                          const std::vector<std::string>& names, bool force);

}  // namespace montecl
