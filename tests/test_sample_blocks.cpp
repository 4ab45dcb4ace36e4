// test_sample_blocks.cpp: the wave item order (kernels/stages/stage_common.h): blocks of
// C = 2^shift samples per pixel. The mapping from a round's items to (pixel, sample) is a bijection
// onto active x [first, first + spp), a pixel's items come in sample order, C consecutive items
// are one pixel's when the round is aligned, and accumulate's work items (touched pixels and their
// runs, wave by wave) visit every item of the round exactly once. Then renders: with blocks of
// 4, 8 and 16 samples, fixed wave sizes that cut blocks, and every integrator, the OpenCL device at
// W = 16 and W = 4 gives the host backend's bytes (the host runs C = 1).
#include <doctest/doctest.h>

#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "lanes_vs_host.h"
#include "kernels/stages/stage_common.h"
#include "skip.h"

namespace test_file_sample_blocks {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;

TEST_CASE("sample blocks: the block shift divides the round, at most the lane width" * doctest::test_suite("cpu")) {
  CHECK(sample_block_shift(16, 0, 1024) == 4);
  CHECK(sample_block_shift(8, 0, 1024) == 3);
  CHECK(sample_block_shift(1, 0, 1024) == 0);
  CHECK(sample_block_shift(16, 0, 24) == 3);
  CHECK(sample_block_shift(16, 4, 32) == 2);
  CHECK(sample_block_shift(16, 0, 13) == 0);
  CHECK(sample_block_shift(16, 1, 16) == 0);
}

TEST_CASE("sample blocks: items map one to one onto (pixel, sample), in sample order per pixel" *
          doctest::test_suite("cpu")) {
  struct Case {
    unsigned pixels, lanes;
    std::uint64_t first, spp;
    std::vector<unsigned> waves;  // wave sizes, repeated until the round is done
  };
  const Case cases[] = {{7, 16, 0, 32, {5}},      {100, 16, 16, 48, {64, 37}}, {3, 4, 8, 12, {1000}},
                        {50, 8, 0, 24, {13}},     {20, 16, 0, 13, {7}},        {1, 16, 0, 64, {16, 3}},
                        {33, 16, 32, 16, {33 * 16}}};
  for (const Case& c : cases) {
    CAPTURE(c.pixels);
    CAPTURE(c.first);
    CAPTURE(c.spp);
    const unsigned shift = sample_block_shift(c.lanes, c.first, c.spp);
    FrameParams f{};
    f.activeCount = c.pixels;
    f.sampleBlockShift = shift;
    std::vector<uint> active(c.pixels);
    for (unsigned p = 0; p < c.pixels; ++p) active[p] = (2 * c.pixels - 1 - p + 3) % c.pixels;  // out of order
    const std::uint64_t start = c.first * c.pixels, total = c.spp * c.pixels;
    std::map<std::pair<uint, uint>, int> seen;
    std::map<uint, std::vector<uint>> order;  // per pixel: samples in item order
    std::vector<int> accumulated(total, 0);
    std::uint64_t done = 0;
    for (std::size_t w = 0; done < total; ++w) {
      const uint n = uint(std::min<std::uint64_t>(c.waves[w % c.waves.size()], total - done));
      const std::uint64_t ws = start + done;
      for (uint i = 0; i < n; ++i) {
        const uint p = item_pixel(&f, active.data(), ws, i), s = item_sample(&f, ws, i);
        seen[{p, s}]++;
        order[p].push_back(s);
        if (i > 0 && shift > 0 && (ws + i) % (1u << shift) != 0)
          CHECK(p == item_pixel(&f, active.data(), ws, i - 1));  // within a block: one pixel
      }
      // accumulate's enumeration: touched pixel j, its runs, their items.
      const uint touched = wave_touched_pixels(ws, n, shift, c.pixels);
      for (uint j = 0; j < touched; ++j) {
        const uint pixel = active[uint(((ws >> shift) + j) % c.pixels)];
        for (std::uint64_t q = (ws >> shift) + j; (q << shift) < ws + n; q += c.pixels) {
          uint a = 0, b = 0;
          wave_run_items(ws, n, shift, q, &a, &b);
          for (uint i = a; i < b; ++i) {
            CHECK(item_pixel(&f, active.data(), ws, i) == pixel);
            accumulated[done + i]++;
          }
        }
      }
      done += n;
    }
    CHECK(seen.size() == total);
    for (const auto& [key, times] : seen) {
      CHECK(times == 1);
      CHECK(key.second >= c.first);
      CHECK(key.second < c.first + c.spp);
    }
    for (const auto& [pixel, samples] : order)
      for (std::size_t k = 1; k < samples.size(); ++k) CHECK(samples[k] == samples[k - 1] + 1);
    for (std::uint64_t g = 0; g < total; ++g) CHECK(accumulated[g] == 1);
  }
}

TEST_CASE("sample blocks: renders with blocks of 4, 8, 16 samples and cut waves match the host backend" *
          doctest::test_suite("cli")) {
  const std::string scene = sharedScenes() + "/cornell-box/scene.json";
  MCL_SKIP_UNLESS(std::ifstream(scene).good(), "no shared Cornell box at " << scene);
  TempDir dir;
  // (integrator, spp, wave size): spp 16, 24, 20 give C = 16, 8, 4 at W = 16; waves of 1000 and
  // 333 items cut the blocks (scalar accumulate); "" is the planned default.
  const std::tuple<const char*, const char*, const char*> configs[] = {
      {"ao", "16", ""}, {"direct", "24", "1000"}, {"path", "20", "333"}, {"direct", "16", ""}, {"path", "16", ""}};
  for (const auto& row : configs) {
    const auto& integrator = std::get<0>(row);
    const auto& spp = std::get<1>(row);
    const auto& wave = std::get<2>(row);
    CAPTURE(integrator);
    CAPTURE(spp);
    CAPTURE(wave);
    std::vector<std::string> common = {"render", scene, "-q", "--width", "19", "--height", "13",
                                       "--integrator", integrator, "--spp", spp, "--overwrite"};
    if (*wave) common.insert(common.end(), {"--wave-size", wave});
    checkLanesMatchHost(common, dir, {"16", "4"});
  }
}

}  // namespace test_file_sample_blocks
