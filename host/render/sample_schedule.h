// sample_schedule.h: which pixels get which samples next. Each pixel's schedule depends only on
// its own count and state: without adaptive sampling it needs samples up to spp; with it, rounds
// end at minSpp, 2 minSpp, 4 minSpp ... maxSpp, and at each round's end the pixel goes on while
// its relative error exceeds the target. A fresh render is one round (or the adaptive rounds); a
// resumed film (pixels at different counts) first brings the lowest counts up; the relative error
// the adaptive rule compares (relativeStandardError). Reads the film it is given; writes nothing
// else.
#pragma once
#include <cstdint>
#include <vector>

#include "image/film.h"

namespace montecl {

struct RenderOptions;
struct RenderPart;

// Relative standard error of pixel p's mean luminance (infinite below 2 samples).
double relativeStandardError(const Film& film, std::size_t p, double errorFloor);

class SampleSchedule {
 public:
  // The pixels this render owns (part.pixels, or all), counts from part.initialFilm.
  SampleSchedule(const RenderOptions& options, const RenderPart& part, std::uint64_t pixels, int spp);

  // The next group, from the film as it stands: the owned pixels with the lowest count that still
  // need samples (active), that count (from) and the count they all reach next (to); remaining:
  // the samples every owned pixel still needs by its current target. False when none needs any.
  bool next(const Film& film, std::vector<std::uint32_t>& active, std::uint64_t& from, std::uint64_t& to,
            std::uint64_t& remaining);
  // The group of next() rendered its samples.
  void done(const std::vector<std::uint32_t>& active, std::uint64_t to);
  // Frees next()'s per-pixel targets (before the film is read back: the peak).
  void releaseTargets() { std::vector<std::uint64_t>().swap(target_); }
  // After a render stopped early: whether any owned pixel of the film still needs samples.
  bool unfinished(const Film& film);

 private:
  std::uint64_t nextTarget(const Film& film, std::uint32_t p) const;  // 0: done

  const RenderOptions& o_;
  const std::uint64_t spp_;
  std::vector<std::uint32_t> mine_;
  std::vector<std::uint64_t> counts_, target_;
};

}  // namespace montecl
