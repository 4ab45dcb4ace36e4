// sample_schedule.cpp: the per-pixel sample schedule (sample_schedule.h).
#include "render/sample_schedule.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/render_options.h"

namespace montecl {

SampleSchedule::SampleSchedule(const RenderOptions& options, const RenderPart& part, std::uint64_t pixels, int spp,
                               bool budget, int splits)
    : o_(options), spp_(std::uint64_t(spp)), budget_(budget), mine_(part.pixels), counts_(pixels, 0), target_(pixels, 0) {
  if (mine_.empty())
    for (std::uint64_t p = 0; p < pixels; ++p) mine_.push_back(std::uint32_t(p));
  if (part.initialFilm) counts_ = part.initialFilm->count;
  if (options.targetError > 0.0 && options.minSpp > options.maxSpp) throw std::invalid_argument("minSpp > maxSpp");
  if (budget_) {
    if (options.targetError > 0.0) throw std::invalid_argument("a budget and a target error");
    rule_.firstPass = std::min<std::uint64_t>(std::uint64_t(std::max(options.minSpp, 1)), spp_);
    rule_.maxSpp = std::uint64_t(std::max(options.maxSpp, 1));
    rule_.total = spp_ * mine_.size();
    rule_.quantum = std::uint64_t(std::max(splits, 1));
    // A resumed render finishes the round it was in (the targets its checkpoint kept).
    if (part.initialFilm && part.initialFilm->roundTarget.size() == pixels) round_ = part.initialFilm->roundTarget;
    else round_.assign(pixels, 0);
  }
}

bool SampleSchedule::roundOver() const {
  return std::none_of(mine_.begin(), mine_.end(), [&](std::uint32_t p) { return round_[p] > counts_[p]; });
}

bool SampleSchedule::needsFilm() const { return o_.targetError > 0.0 || (budget_ && roundOver()); }

std::uint64_t SampleSchedule::nextTarget(const Film& film, std::uint32_t p) const {
  const std::uint64_t c = counts_[p];
  if (budget_) return round_[p] > c ? round_[p] : 0;
  if (!(o_.targetError > 0.0)) return c < spp_ ? spp_ : 0;
  const std::uint64_t minSpp = std::uint64_t(o_.minSpp), maxSpp = std::uint64_t(o_.maxSpp);
  if (c < minSpp) return minSpp;
  std::uint64_t bound = minSpp;
  while (bound < c) bound = std::min(2 * bound, maxSpp);
  if (bound > c) return bound;  // within a round
  if (c >= maxSpp || relativeStandardError(film, p, o_.errorFloor) <= o_.targetError) return 0;
  return std::min(2 * c, maxSpp);
}

bool SampleSchedule::next(const Film& film, std::vector<std::uint32_t>& active, std::uint64_t& from,
                          std::uint64_t& to, std::uint64_t& remaining) {
  if (budget_ && roundOver() && nextAdaptiveRound(film, mine_, counts_, rule_, round_) == 0) return false;
  std::uint64_t low = UINT64_MAX;
  remaining = 0;
  for (std::uint32_t p : mine_) {
    target_[p] = nextTarget(film, p);
    if (target_[p]) low = std::min(low, counts_[p]), remaining += target_[p] - counts_[p];
  }
  if (low == UINT64_MAX) return false;
  if (budget_) {  // the progress bar's total: the budget, not this round's end
    std::uint64_t done = 0;
    for (std::uint32_t p : mine_) done += counts_[p];
    remaining = std::max(remaining, rule_.total > done ? rule_.total - done : 0);
  }
  std::uint64_t upTo = UINT64_MAX;  // the lowest group's target, or the next count above it
  active.clear();
  for (std::uint32_t p : mine_) {
    if (!target_[p]) continue;
    if (counts_[p] == low) active.push_back(p), upTo = std::min(upTo, target_[p]);
    else upTo = std::min(upTo, counts_[p]);
  }
  from = low;
  to = upTo;
  return true;
}

void SampleSchedule::done(const std::vector<std::uint32_t>& active, std::uint64_t to) {
  for (std::uint32_t p : active) counts_[p] = to;
}

bool SampleSchedule::unfinished(const Film& film) {
  for (std::uint32_t p : mine_) counts_[p] = film.count[p];
  if (budget_) {  // the round unfinished, or the budget has room for another
    if (!roundOver()) return true;
    std::vector<std::uint64_t> probe(round_);
    return nextAdaptiveRound(film, mine_, counts_, rule_, probe) != 0;
  }
  return std::any_of(mine_.begin(), mine_.end(), [&](std::uint32_t p) { return nextTarget(film, p) != 0; });
}

double relativeStandardError(const Film& film, std::size_t p, double errorFloor) {
  const double n = double(film.count[p]);
  if (n < 2.0) return INFINITY;
  const glm::dvec3 w(0.2126, 0.7152, 0.0722);
  // Luminance of each sample is a linear combination of its channels; its variance needs the
  // cross terms, which are not accumulated, so the channels' standard errors are combined as if
  // fully correlated (an upper bound): se(L) <= sum_c w_c se_c.
  double mean = 0.0, se = 0.0;
  for (int c = 0; c < 3; ++c) {
    mean += w[c] * film.mean[p][c];
    se += w[c] * std::sqrt(film.meanVariance(p, c));
  }
  return se / std::max(mean, errorFloor);
}

}  // namespace montecl
