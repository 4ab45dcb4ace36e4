// test_wave_queue.cpp: waves queued ahead (StageRunner::submitWave / waitWave): two waves in
// flight return their own counts, oldest first, on OpenCL and on the host backend; and a render
// whose waves are queued ahead (no time limit, no afterWave) books the same image, counts and
// progress as one whose waves are booked one by one (afterWave set).
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "render/frame_params.h"
#include "render/stage_runner.h"
#include "render/wavefront.h"
#include "test_scenes.h"

namespace test_file_wave_queue {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

// Two AO waves of all-NaN camera rays (each ray is counted as non-finite) of different
// sizes, the second queued before the first is waited for.
void checkTwoInFlight(StageRunner& run) {
  const Scene scene = floorScene({0, 0, 0}, 1.0f, 60.0f, 16, 1);
  const Bvh bvh = buildBvh(scene.triangles);
  StageInputs in;
  in.frame = makeFrameParams(scene.camera, scene.render, 1);
  in.frame.camTopLeft = glm::vec4(std::nanf(""), 0.0f, 1.0f, 0.0f);
  in.bvh = &bvh;
  in.materials = std::vector<Material>(1);
  in.shape.items = 256;
  run.setup(in);
  std::uint64_t start = 0;
  for (std::uint32_t n : {100u, 156u}) {
    run.beginWave(start, n);
    for (Stage s : {Stage::generate, Stage::intersect, Stage::shade_ao, Stage::intersect_shadow, Stage::accumulate})
      run.launch(s, n);
    run.submitWave();
    start += n;
  }
  CHECK(run.waitWave().nanRays == 100);
  CHECK(run.waitWave().nanRays == 156);
  Film film;
  run.finish(film);
  for (std::uint64_t c : film.count) CHECK(c == 1u);  // every pixel got its one sample
}

struct Run {
  Film film;
  RenderStats stats;
  std::vector<std::uint64_t> done;  // the progress callback's `done`, call by call
};

Run render(const Scene& scene, bool oneByOne) {
  static const DeviceInfo device = selectDevice("");
  const Bvh bvh = buildBvh(scene.triangles);
  RenderOptions options;
  options.waveSize = 97;
  RenderPart part;
  if (oneByOne) part.afterWave = [](const std::function<Film()>&) {};
  WavefrontRenderer renderer(device, options);
  Run r;
  r.film = renderer.render(scene, bvh, r.stats, [&](std::uint64_t done, std::uint64_t, const RenderStats&) {
    r.done.push_back(done);
  }, part);
  return r;
}

}  // namespace

TEST_CASE("wave queue: two waves in flight return their own counts, oldest first (OpenCL)" *
          doctest::test_suite("opencl")) {
  checkTwoInFlight(*makeClStageRunner(selectDevice(""), 0));
}

TEST_CASE("wave queue: two waves in flight return their own counts, oldest first (host backend)" *
          doctest::test_suite("cpu")) {
  checkTwoInFlight(*makeHostStageRunner());
}

TEST_CASE("wave queue: waves queued ahead book the image, counts and progress of waves booked one by one" *
          doctest::test_suite("opencl")) {
  Scene demo = montecl_test::smallDemoScene(24, 16, 3);
  for (Integrator integrator : {Integrator::Ao, Integrator::Direct}) {
    CAPTURE(int(integrator));
    Scene s = demo;
    s.render.integrator = integrator;
    const Run ahead = render(s, false), oneByOne = render(s, true);
    CHECK(ahead.film.mean == oneByOne.film.mean);
    CHECK(ahead.film.m2 == oneByOne.film.m2);
    CHECK(ahead.film.count == oneByOne.film.count);
    CHECK(ahead.stats.waves == (24 * 16 * 3 + 96) / 97);
    CHECK(ahead.stats.waves == oneByOne.stats.waves);
    CHECK(ahead.stats.samples == oneByOne.stats.samples);
    CHECK(ahead.stats.cameraRays == oneByOne.stats.cameraRays);
    CHECK(ahead.stats.shadowRays > 0);
    CHECK(ahead.stats.shadowRays == oneByOne.stats.shadowRays);
    CHECK(ahead.done == oneByOne.done);
  }
}

TEST_CASE("wave queue: a render that throws with a wave queued leaves the renderer ready for the next" *
          doctest::test_suite("opencl")) {
  Scene s = wallScene(20, 6);
  const Bvh bvh = buildBvh(s.triangles);
  RenderOptions options;
  options.waveSize = 97;  // 25 waves, queued ahead (no time limit, no afterWave)
  WavefrontRenderer renderer(selectDevice(""), options);
  RenderStats stats;
  int calls = 0;
  CHECK_THROWS_AS(renderer.render(s, bvh, stats,
                                  [&](std::uint64_t, std::uint64_t, const RenderStats&) {
                                    if (++calls == 3) throw std::runtime_error("stop");
                                  }),
                  std::runtime_error);
  CHECK(calls == 3);
  const Film again = renderer.render(s, bvh, stats);
  CHECK(stats.waves == 25);
  WavefrontRenderer fresh(selectDevice(""), options);
  const Film reference = fresh.render(s, bvh, stats);
  CHECK(again.mean == reference.mean);
  CHECK(again.count == reference.count);
}

}  // namespace test_file_wave_queue
