// sample_schedule.h: which pixels get which samples next. Each pixel's schedule depends only on
// its own count and state: without adaptive sampling it needs samples up to spp; with it, rounds
// end at minSpp, 2 minSpp, 4 minSpp ... maxSpp, and at each round's end the pixel goes on while
// its relative error exceeds the target. Under a budget (render.adaptive) each round's targets
// come from the whole film at the round's start (render/adaptive_budget.h) and are kept (a
// checkpoint holds them: Film::roundTarget). A fresh render is one round (or the adaptive rounds); a
// resumed film (pixels at different counts) first brings the lowest counts up; the relative error
// the adaptive rule compares (relativeStandardError). Reads the film it is given; writes nothing
// else.
#pragma once
#include <cstdint>
#include <vector>

#include "image/film.h"
#include "render/adaptive_budget.h"

namespace montecl {

struct RenderOptions;
struct RenderPart;

// Relative standard error of pixel p's mean luminance (infinite below 2 samples).
double relativeStandardError(const Film& film, std::size_t p, double errorFloor);

class SampleSchedule {
 public:
  // The pixels this render owns (part.pixels, or all), counts from part.initialFilm.
  // budget: render.adaptive (the rounds of adaptive_budget.h, spp the average), with `splits`
  // sub-sequences per pixel (a round adds multiples of them).
  SampleSchedule(const RenderOptions& options, const RenderPart& part, std::uint64_t pixels, int spp,
                 bool budget = false, int splits = 1);

  // Whether next() needs the film as it stands (the target-error rule reads it for every group; a
  // budget's rounds at their start only).
  bool needsFilm() const;

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
  // Under a budget: each pixel's target in the current round (all pixels; empty otherwise).
  const std::vector<std::uint64_t>& roundTargets() const { return round_; }

 private:
  std::uint64_t nextTarget(const Film& film, std::uint32_t p) const;  // 0: done

  bool roundOver() const;

  const RenderOptions& o_;
  const std::uint64_t spp_;
  const bool budget_;
  AdaptiveBudget rule_;
  std::vector<std::uint32_t> mine_;
  std::vector<std::uint64_t> counts_, target_, round_;
};

}  // namespace montecl
