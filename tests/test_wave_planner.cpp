// test_wave_planner.cpp: the wave planner (render/wave_planner.h) as a pure function: simulated
// renders at known (and varying) rates end near the time limit, waves stay under the cap and
// near the aimed duration; and through the real wave loop: the progress callback comes once per
// wave, waves never exceed the cap, and planned (rate-sized) waves give bit-identical images to
// fixed ones for AO, direct and path.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "cl/device_tuning.h"
#include "cl/devices.h"
#include "kernels/stages/stage_common.h"
#include "render/wave_planner.h"
#include "render/wavefront.h"
#include "scene/scene.h"
#include "test_scenes.h"

namespace test_file_wave_planner {  // keeps this file's helpers apart in a unity batch

using namespace montecl;

namespace {

struct Simulated {
  double seconds = 0.0;
  std::uint64_t items = 0, waves = 0, largest = 0;
  double longestWave = 0.0;
  bool stopped = false;  // the planner returned 0 before the items ran out
};

// A render of `total` items whose true rate during wave w is rateOf(w), with `overhead` seconds
// per wave; rate as the wave loop measures it (items / wave seconds).
template <class RateOf>
Simulated simulate(const WavePlanner& planner, std::uint64_t cap, std::uint64_t total, double limit, RateOf rateOf,
                   double overhead = 0.0) {
  Simulated s;
  double rate = 0.0;
  while (s.items < total) {
    const double left = limit > 0.0 ? limit - s.seconds : INFINITY;
    const std::uint64_t n = planWave(planner, cap, total - s.items, rate, left);
    if (n == 0) {
      s.stopped = true;
      break;
    }
    REQUIRE(n <= cap);
    REQUIRE(n <= total - s.items);
    const double took = double(n) / rateOf(s.waves) + overhead;
    s.seconds += took;
    s.items += n;
    s.waves++;
    s.largest = std::max(s.largest, n);
    if (s.waves > 1) s.longestWave = std::max(s.longestWave, took);
    rate = double(n) / took;
    if (limit > 0.0 && s.seconds >= limit) break;  // the loop's own stop after a wave
  }
  return s;
}

}  // namespace

TEST_CASE("wave planner: waves at a steady rate end within 2% of the time limit, each about waveSeconds" *
          doctest::test_suite("cpu")) {
  const WavePlanner planner;  // 0.25 s waves
  for (double rate : {2e4, 3e5, 5e6, 4e7}) {
    for (double limit : {0.3, 1.0, 2.7, 10.0}) {
      CAPTURE(rate);
      CAPTURE(limit);
      const std::uint64_t cap = 1u << 18;
      Simulated s = simulate(planner, cap, ~0ull >> 8, limit, [&](std::uint64_t) { return rate; }, 2e-4);
      CHECK(std::fabs(s.seconds - limit) <= 0.02 * limit);
      CHECK(s.largest <= cap);
      // Waves after the first last at most waveSeconds (plus the overhead).
      CHECK(s.longestWave <= planner.waveSeconds + 1e-3);
    }
  }
}

TEST_CASE("wave planner: a first wave slowed by a compile and a rate that swings by 25% still end within 10%" *
          doctest::test_suite("cpu")) {
  const WavePlanner planner;
  for (double limit : {1.0, 3.0}) {
    CAPTURE(limit);
    // Wave 0 runs 10x slower (a kernel build); then the rate swings between 1e5 and 1.25e5 items/s.
    Simulated s = simulate(planner, 1u << 18, ~0ull >> 8, limit,
                           [](std::uint64_t w) { return w == 0 ? 1e4 : (w % 2 == 0 ? 1e5 : 1.25e5); }, 1e-3);
    CHECK(std::fabs(s.seconds - limit) <= 0.1 * limit);
    CHECK(s.waves >= 2 * limit);  // the progress bar moves at least twice a second
  }
}

TEST_CASE("wave planner: without a limit waves aim at waveSeconds within [minWave, cap]; 0 once time is up" *
          doctest::test_suite("cpu")) {
  WavePlanner p;
  p.waveSeconds = 0.25;
  p.firstWave = 4096;
  p.minWave = 1024;
  CHECK(planWave(p, 1u << 18, 1u << 30, 0.0, INFINITY) == 4096);        // no rate yet: the first wave
  CHECK(planWave(p, 1000, 1u << 30, 0.0, INFINITY) == 1000);            // ... under the cap
  CHECK(planWave(p, 1u << 18, 1u << 30, 4e5, INFINITY) == 100000);      // 0.25 s at 4e5 items/s
  CHECK(planWave(p, 1u << 18, 1u << 30, 4e7, INFINITY) == (1u << 18));  // capped
  CHECK(planWave(p, 1u << 18, 1u << 30, 10.0, INFINITY) == 1024);       // at least minWave
  CHECK(planWave(p, 1u << 18, 77, 4e5, INFINITY) == 77);                // what is left
  CHECK(planWave(p, 1u << 18, 1u << 30, 4e5, 0.0) == 0);                // the limit has passed
  CHECK(planWave(p, 1u << 18, 1u << 30, 4e5, -1.0) == 0);
  CHECK(planWave(p, 1u << 18, 1u << 30, 4e5, 1e-3) == 0);               // 400 items left: under minWave / 2
  CHECK(planWave(p, 1u << 18, 1u << 30, 4e5, 0.1) == 40000);            // the last wave ends at the limit
  CHECK(planWave(p, 1u << 18, 1u << 30, 4e5, 1.0) == 100000);           // 4 waves of 0.25 s
  CHECK(planWave(p, 1u << 18, 0, 4e5, 1.0) == 0);                       // nothing left
}

namespace {

struct Run {
  Film film;
  RenderStats stats;
  std::vector<std::uint64_t> done;  // the progress callback's `done`, call by call
};

Run render(const Scene& scene, const RenderOptions& options) {
  static const DeviceInfo device = selectDevice("");
  Bvh bvh = buildBvh(scene.triangles);
  WavefrontRenderer renderer(device, options);
  Run r;
  r.film = renderer.render(scene, bvh, r.stats, [&](std::uint64_t done, std::uint64_t, const RenderStats&) {
    r.done.push_back(done);
  });
  return r;
}

bool sameFilm(const Film& a, const Film& b) { return a.mean == b.mean && a.m2 == b.m2 && a.count == b.count; }

}  // namespace

TEST_CASE("planned waves: progress after every wave of at most the cap, and the image of fixed waves" *
          doctest::test_suite("opencl")) {
  Scene demo = montecl_test::smallDemoScene(24, 16, 3);
  Scene wall = montecl::wallScene(20, 6);
  for (Integrator integrator : {Integrator::Ao, Integrator::Direct, Integrator::Path}) {
    Scene s = integrator == Integrator::Ao ? wall : demo;
    s.render.integrator = integrator;
    CAPTURE(int(integrator));
    const std::uint64_t total = std::uint64_t(s.camera.width) * s.camera.height * s.render.spp;
    RenderOptions fixed;
    fixed.waveSize = 97;
    Run reference = render(s, fixed);
    CHECK(reference.done.size() == (total + 96) / 97);  // fixed: one callback per wave of 97
    // Planned waves under a cap of 200 items, re-sized after every wave from the measured rate
    // (waves of ~20 us, so their sizes vary with the machine's noise), and with a time limit far
    // away (the time-split plan).
    for (double limit : {0.0, 1e6}) {
      CAPTURE(limit);
      RenderOptions o;
      o.maxWaveItems = 200;
      o.planner.waveSeconds = 2e-5;
      o.planner.firstWave = 13;
      o.planner.minWave = 1;
      o.timeLimit = limit;
      Run r = render(s, o);
      CHECK(sameFilm(r.film, reference.film));
      CHECK(r.stats.waveSize == 200);
      CHECK_FALSE(r.stats.stoppedEarly);
      REQUIRE(r.done.size() == r.stats.waves);  // one callback per wave
      REQUIRE(r.done.size() >= (total + 199) / 200);
      // The first wave: the planner's 13 items, whole blocks of the round's samples per pixel
      // (kernels/stages/stage_common.h; blocks of one sample under a time limit).
      const std::uint64_t block =
          limit > 0.0 ? 1 : std::uint64_t(1) << sample_block_shift(resolveLanes(0, selectDevice("")), 0, s.render.spp);
      CHECK(r.done.front() == (block < 13 ? 13 - 13 % block : 13));
      std::uint64_t last = 0;
      for (std::uint64_t d : r.done) {
        CHECK(d > last);
        CHECK(d - last <= 200);
        last = d;
      }
      CHECK(last == total);
    }
  }
}

}  // namespace test_file_wave_planner
