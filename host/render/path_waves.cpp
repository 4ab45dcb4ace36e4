// path_waves.cpp: the bounce loop of a path-tracing wave. Each bounce is launched over the live
// paths only: the host reads the next queue's size back after every bounce (one small blocking
// read) and sizes the next launches by it, and stops when no path is left. The alternative,
// full-size launches whose items past the device-side count return at once, with a read only every
// 4 bounces to stop, was measured slower: Cornell box 256x256, 32 spp, PoCL on 2 shared cores,
// 6.06-6.44 s with the read-back against 7.97-8.07 s full-size (3 runs each): past the Russian
// roulette depth a few percent of the paths are left, and full-size launches still walk the wave.
#include "render/path_waves.h"

#include <cstdio>

namespace montecl {

std::string survivorsSummary(const std::vector<std::uint64_t>& survivors) {
  std::string s = "paths per bounce (bounce: paths, % of camera rays):";
  for (std::size_t b = 0; b < survivors.size(); ++b) {
    char item[64];
    std::snprintf(item, sizeof item, " %zu: %llu (%.3g%%)", b, static_cast<unsigned long long>(survivors[b]),
                  survivors[0] ? 100.0 * double(survivors[b]) / double(survivors[0]) : 0.0);
    s += item;
  }
  return s;
}

void runPathWave(StageRunner& run, std::uint32_t n, std::uint32_t lightSamples, bool aovs, bool fused,
                 PathWaveCounts& counts) {
  std::uint32_t live = n;
  const std::uint64_t group = std::uint64_t(run.lanes()) * MCL_FUSED_PATH_PACKETS;
  for (std::uint32_t bounce = 0; live > 0; ++bounce) {
    run.startBounce(bounce);
    if (fused) {
      run.launch(Stage::wave_path, (live + group - 1) / group);
    } else {
#define MCL_HOST_STEP(stage, rays, queries) run.launch(Stage::stage, live, RayInput::rays);
      MCL_SCHEDULE_path(MCL_HOST_STEP)
#undef MCL_HOST_STEP
      // Camera rays and hits (identity ids), and radiance holding only the camera ray's own term:
      // after shade_path, before path_gather adds the light samples (record_aov.h).
      if (bounce == 0 && aovs) run.launch(Stage::record_aov, n);
      run.launch(Stage::intersect_shadow, std::uint64_t(live) * lightSamples);
      run.launch(Stage::path_gather, live);
    }
    run.endBounce();
    const BounceCounts c = run.readBounceCounts();
    if (counts.survivors.size() <= bounce) counts.survivors.resize(bounce + 1, 0);
    counts.survivors[bounce] += live;
    if (bounce > 0) counts.bounceRays += live;
    counts.shadowRays += c.shadowRays;
    live = c.paths;
  }
}

}  // namespace montecl
