// progress.h: the progress bar on stderr (only on a terminal, unless quiet) and the final
// summary line.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "render/wavefront.h"

namespace montecl {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);  // enabled && stderr is a terminal
  void update(std::uint64_t done, std::uint64_t total, const RenderStats& stats);
  void finish();  // ends the bar's line

 private:
  bool enabled_;
  bool drawn_ = false;
};

// "512x512, 64 spp: 1.23 s, 33.6 M rays, 27.3 Mrays/s"
std::string summaryLine(int width, int height, int spp, const RenderStats& stats);

// After --resume the summary line's spp are this run's only; this says what the image holds, from
// the film's per-pixel sample counts: "; the image now holds 64 spp" or "; the image now holds
// 53.3 spp on average (48..64 per pixel)".
std::string imageSamplesNote(const std::vector<std::uint64_t>& count);

}  // namespace montecl
