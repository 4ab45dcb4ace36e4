// test_render_memory.cpp: what lowers a render's peak memory keeps the image: StageRunner::finish
// (the last film read, which releases every buffer, the film's part by part) returns what
// readFilm returns and leaves the runner ready for another setup, on OpenCL (where the scene's
// arrays are used in place on CPU devices) and on the host backend; and a render whose caller
// renders from prepared triangles with the scene's own freed gives the same image.
#include <doctest/doctest.h>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "render/frame_params.h"
#include "render/stage_runner.h"
#include "render/wavefront.h"
#include "test_scenes.h"

namespace test_file_render_memory {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;

namespace {

bool sameFilm(const Film& a, const Film& b) {
  return a.mean == b.mean && a.meanLo == b.meanLo && a.m2 == b.m2 && a.m2Lo == b.m2Lo && a.count == b.count &&
         a.aovSum == b.aovSum;
}

// Two AO waves (every pixel once each, AOVs on) after a fresh setup; the film by readFilm
// (*before, when given) and then by finish.
Film twoWaves(StageRunner& run, const Scene& scene, const Bvh& bvh, Film* before) {
  StageInputs in;
  in.frame = makeFrameParams(scene.camera, scene.render, 1);
  in.bvh = &bvh;
  Material grey{};
  const float noTexture = glm::uintBitsToFloat(MCL_NO_TEXTURE);
  grey.albedo = glm::vec4(0.5f, 0.5f, 0.5f, noTexture);
  grey.alpha = glm::vec4(noTexture, 0.0f, 0.0f, 0.0f);
  grey.maps = glm::vec4(noTexture, noTexture, 0.0f, 0.0f);  // no emission or metallic-roughness texture
  in.materials = {grey};
  in.shape.items = in.frame.width * in.frame.height;
  in.shape.aovs = true;
  run.setup(in);
  const std::uint32_t n = std::uint32_t(in.shape.items);
  for (std::uint64_t start : {std::uint64_t(0), std::uint64_t(n)}) {
    run.beginWave(start, n);
    for (Stage s : {Stage::generate, Stage::intersect, Stage::shade_ao, Stage::intersect_shadow, Stage::record_aov,
                    Stage::accumulate, Stage::accumulate_aov})
      run.launch(s, n);
    run.submitWave();
    run.waitWave();
  }
  Film film;
  film.width = int(in.frame.width);
  film.height = int(in.frame.height);
  if (before) *before = film, run.readFilm(*before);
  run.finish(film);
  return film;
}

void checkFinish(StageRunner& run) {
  Scene s = wallScene(12, 2);
  s.render.aoSampling = AoSampling::Uniform;
  const Bvh bvh = buildBvh(s.triangles);
  Film read;
  const Film first = twoWaves(run, s, bvh, &read);
  REQUIRE(first.count.size() == 144);
  CHECK(first.count[0] == 2u);
  CHECK(first.aovSum.size() == MCL_AOV_VECTORS * 144);
  CHECK(sameFilm(first, read));
  CHECK(sameFilm(twoWaves(run, s, bvh, nullptr), first));  // set up again after finish: the same
  s.render.seed = 1;
  CHECK_FALSE(sameFilm(twoWaves(run, s, bvh, nullptr), first));  // (the comparison can fail)
}

Film renderDemo(const DeviceInfo& device, bool freeTriangles, int* calls) {
  Scene scene = montecl_test::smallDemoScene(24, 16, 3);
  scene.render.integrator = Integrator::Direct;
  const Bvh bvh = buildBvh(scene.triangles);
  RenderOptions options;
  options.waveSize = 100;
  RenderPart part;
  PreparedTriangles prepared;
  if (freeTriangles) {  // as montecl render does: prepared, then freed before the render
    prepared = prepareTriangles(scene, bvh);
    part.triangles = &prepared;
    std::vector<SceneTriangle>().swap(scene.triangles);
    ++*calls;
  }
  WavefrontRenderer renderer(device, options);
  RenderStats stats;
  Film film = renderer.render(scene, bvh, stats, {}, part);
  CHECK(scene.triangles.empty() == freeTriangles);
  return film;
}

void checkPreparedTriangles(const DeviceInfo& device) {
  int kept = 0, freed = 0;
  const Film reference = renderDemo(device, false, &kept);
  CHECK(kept == 0);
  CHECK(sameFilm(renderDemo(device, true, &freed), reference));
  CHECK(freed == 1);
}

}  // namespace

TEST_CASE("render memory: finish() reads what readFilm reads, and the runner sets up again (OpenCL)" *
          doctest::test_suite("opencl")) {
  for (BvhLayout layout : {BvhLayout::Wide, BvhLayout::Binary}) {
    CAPTURE(int(layout));
    checkFinish(*makeClStageRunner(selectDevice(""), 0, layout));
  }
  checkPreparedTriangles(selectDevice(""));
}

TEST_CASE("render memory: finish() and prepared triangles on the host backend" * doctest::test_suite("cpu")) {
  checkFinish(*makeHostStageRunner());
  checkPreparedTriangles(selectDevice("host"));
}

}  // namespace test_file_render_memory
