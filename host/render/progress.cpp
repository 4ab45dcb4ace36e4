// progress.cpp: a one-line progress bar (samples done, Mrays/s, ETA) redrawn with '\r'.
#include "render/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace montecl {

ProgressBar::ProgressBar(bool enabled) : enabled_(enabled && isatty(STDERR_FILENO)) {}

void ProgressBar::update(std::uint64_t done, std::uint64_t total, const RenderStats& stats) {
  if (!enabled_ || total == 0) return;
  const int width = 30;
  double frac = double(done) / double(total);
  int filled = int(frac * width + 0.5);
  double mrays = stats.seconds > 0 ? stats.raysTraced() / stats.seconds * 1e-6 : 0.0;
  double eta = frac > 0 ? stats.seconds * (1.0 - frac) / frac : 0.0;
  std::fprintf(stderr, "\r[%.*s%*s] %5.1f%% %llu/%llu samples %7.2f Mrays/s ETA %5.1fs", filled,
               "##############################", width - filled, "", 100.0 * frac,
               (unsigned long long)done, (unsigned long long)total, mrays, eta);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::finish() {
  if (drawn_) std::fprintf(stderr, "\n");
  drawn_ = false;
}

std::string summaryLine(int width, int height, int spp, const RenderStats& stats) {
  char buf[256];
  const double pixels = double(width) * height;
  double mrays = stats.seconds > 0 ? stats.raysTraced() / stats.seconds * 1e-6 : 0.0;
  char sppText[64];
  if (stats.samples == std::uint64_t(pixels) * std::uint64_t(spp))
    std::snprintf(sppText, sizeof sppText, "%d spp", spp);
  else
    std::snprintf(sppText, sizeof sppText, "%.1f spp on average", double(stats.samples) / pixels);
  std::snprintf(buf, sizeof buf, "%dx%d, %s: %.3f s, %.2f M rays, %.2f Mrays/s", width, height, sppText,
                stats.seconds, stats.raysTraced() * 1e-6, mrays);
  return buf;
}

std::string imageSamplesNote(const std::vector<std::uint64_t>& count) {
  if (count.empty()) return "";
  std::uint64_t lo = count[0], hi = count[0], sum = 0;
  for (std::uint64_t n : count) lo = std::min(lo, n), hi = std::max(hi, n), sum += n;
  char buf[128];
  if (lo == hi) std::snprintf(buf, sizeof buf, "; the image now holds %llu spp", (unsigned long long)lo);
  else
    std::snprintf(buf, sizeof buf, "; the image now holds %.1f spp on average (%llu..%llu per pixel)",
                  double(sum) / double(count.size()), (unsigned long long)lo, (unsigned long long)hi);
  return buf;
}

}  // namespace montecl
