// test_denoise.cpp: `montecl render --denoise` (Open Image Denoise, image/oidn_denoiser.h) end to
// end: without the library, with one whose CPU device cannot be created, or with a FIFO named as
// the library it is one line and exit 2 with nothing written, before any work; a filter failing
// after the render leaves the noisy image written with a warning; the EXR keeps the noisy layers
// bit for bit; the denoised Cornell box is closer to a converged reference than the noisy one. The
// cases that run the real filter skip (with the reason) where the library is not installed; the
// failure cases load a stand-in library (tests/fixtures/fake_oidn).
#include <doctest/doctest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "image/oidn_denoiser.h"
#include "sanitizers.h"
#include "skip.h"

namespace test_file_denoise {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;
namespace fs = std::filesystem;

namespace {

std::vector<float> rgbPlanes(const LayeredImage& img, const std::string& prefix) {
  std::vector<float> out;
  for (const char* c : {"R", "G", "B"}) {
    const std::vector<float>* p = img.find(prefix + c);
    REQUIRE_MESSAGE(p, "no channel " << prefix << c);
    out.insert(out.end(), p->begin(), p->end());
  }
  return out;
}

double rmse(const std::vector<float>& a, const std::vector<float>& b) {
  REQUIRE(a.size() == b.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
  return std::sqrt(sum / double(a.size()));
}

}  // namespace

// Under AddressSanitizer the filter cannot run: OIDN's TBB dlopens libtbbbind with RTLD_DEEPBIND,
// which the ASan runtime refuses (google/sanitizers#611), so those cases skip there (the release
// suite runs them).
#if MCL_TEST_UNDER_ASAN
#define MCL_SKIP_UNLESS_OIDN() \
  MCL_SKIP_UNLESS(false, "under AddressSanitizer: OIDN's TBB dlopens libtbbbind with RTLD_DEEPBIND, which ASan refuses")
#else
#define MCL_SKIP_UNLESS_OIDN() \
  MCL_SKIP_UNLESS(oidnProblem().empty(), oidnProblem())
#endif

TEST_CASE("denoise: without the library --denoise is one line naming the set-up command, exit 2, nothing written" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  for (const char* out : {"a.png", "a.exr"}) {
    CliResult r = runMontecl({"render", demoScene(), "-o", dir.file(out), "--width", "8", "--height", "8", "--spp",
                              "1", "--denoise", "-q"},
                             {"MONTECL_OIDN_LIBRARY=" + dir.file("missing/libOpenImageDenoise.so.2")});
    INFO(r.err);
    CHECK(r.exitCode == 2);
    CHECK(r.out.empty());
    CHECK(r.err.find("bash scripts/setup.sh --oidn") != std::string::npos);
    CHECK(r.err.find('\n') == r.err.size() - 1);  // one line
  }
  CHECK(dir.entries().empty());
}

// A library that loads and exports every symbol but cannot create its CPU device (the core copied
// without libOpenImageDenoise_device_cpu) is refused before any work, like a missing one.
TEST_CASE("denoise: a library whose CPU device cannot be committed is one line, exit 2, before any work" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  CliResult r = runMontecl({"render", demoScene(), "-o", dir.file("a.exr"), "--width", "8", "--height", "8", "--spp",
                            "1", "--denoise"},
                           {std::string("MONTECL_OIDN_LIBRARY=") + MONTECL_FAKE_OIDN, "MONTECL_FAKE_OIDN_FAIL=device"});
  INFO(r.err);
  CHECK(r.exitCode == 2);
  CHECK(r.out.empty());
  CHECK(r.err.find("CPU device") != std::string::npos);
  CHECK(r.err.find("no supported devices found") != std::string::npos);
  CHECK(r.err.find('\n') == r.err.size() - 1);  // one line: no progress bar, nothing rendered
  CHECK(dir.entries().empty());
}

// A filter that fails after the render leaves the noisy image written, with a warning.
TEST_CASE("denoise: a filter failing after the render writes the noisy image with a warning" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::vector<std::string> env = {std::string("MONTECL_OIDN_LIBRARY=") + MONTECL_FAKE_OIDN,
                                        "MONTECL_FAKE_OIDN_FAIL=execute"};
  CliResult plain = runMontecl(demoRenderArgs(dir.file("plain.exr"), 2, 0));
  REQUIRE(plain.exitCode == 0);
  for (const char* out : {"a.exr", "a.png"}) {
    std::vector<std::string> args = demoRenderArgs(dir.file(out), 2, 0);
    args.push_back("--denoise");
    CliResult r = runMontecl(args, env);
    INFO(out << ": " << r.err);
    CHECK(r.exitCode == 0);
    CHECK(r.err.find("warning") != std::string::npos);
    CHECK(r.err.find("out of memory while filtering") != std::string::npos);
    REQUIRE(std::ifstream(dir.file(out)).good());
  }
  // The EXR holds the noisy estimate exactly and no denoised planes.
  const LayeredImage a = readLayeredImage(dir.file("plain.exr")), b = readLayeredImage(dir.file("a.exr"));
  CHECK(b.channels == a.channels);
  for (const std::string& ch : a.channels) CHECK(*b.find(ch) == *a.find(ch));
}

// dlopen of a FIFO blocks until a writer opens it: forever. A helper opens it for writing after
// 20 s (then dlopen fails on the empty file), so without the rule the case fails on its time
// instead of hanging; with it the refusal comes at once.
TEST_CASE("denoise: MONTECL_OIDN_LIBRARY naming a FIFO or a folder is one line, exit 2, at once" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  REQUIRE(mkfifo(dir.file("fifo.so").c_str(), 0600) == 0);
  fs::create_directory(dir.file("folder.so"));
  std::atomic<bool> done{false};
  std::thread unblock([&] {
    for (int i = 0; i < 200 && !done; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (done) return;
    const int fd = open(dir.file("fifo.so").c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) close(fd);
  });
  for (const char* lib : {"fifo.so", "folder.so"}) {
    const auto start = std::chrono::steady_clock::now();
    CliResult r = runMontecl({"render", demoScene(), "-o", dir.file("a.png"), "--width", "8", "--height", "8",
                              "--spp", "1", "--denoise", "-q"},
                             {"MONTECL_OIDN_LIBRARY=" + dir.file(lib)});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    INFO(lib << ": " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(r.err.find("is not a regular file") != std::string::npos);
    CHECK(r.err.find('\n') == r.err.size() - 1);
    CHECK(seconds < 10.0);
  }
  done = true;
  unblock.join();
  CHECK_FALSE(fs::exists(dir.file("a.png")));
}

TEST_CASE("denoise: the EXR keeps R, G, B, samples and var bit for bit and adds denoised.R/G/B" *
          doctest::test_suite("cli")) {
  MCL_SKIP_UNLESS_OIDN();
  TempDir dir;
  const std::vector<std::string> base = {"render", demoScene(), "--width", "24", "--height", "16", "--spp", "4", "-q"};
  std::vector<std::string> plain = base, denoised = base;
  plain.insert(plain.end(), {"-o", dir.file("plain.exr")});
  denoised.insert(denoised.end(), {"-o", dir.file("denoised.exr"), "--denoise", "--denoise-quality", "fast"});
  CliResult p = runMontecl(plain), d = runMontecl(denoised);
  INFO(p.err << d.err);
  REQUIRE(p.exitCode == 0);
  REQUIRE(d.exitCode == 0);
  CHECK(d.out.find("denoised in") != std::string::npos);
  const LayeredImage a = readLayeredImage(dir.file("plain.exr")), b = readLayeredImage(dir.file("denoised.exr"));
  for (const std::string& ch : a.channels) {
    INFO(ch);
    REQUIRE(b.find(ch));
    CHECK(*b.find(ch) == *a.find(ch));  // exact: the AOVs the filter needs change no estimate
  }
  // Only denoised.R/G/B are added (the guides are not written unless --aov asks).
  CHECK(b.channels.size() == a.channels.size() + 3);
  const std::vector<float> rgb = rgbPlanes(b, "denoised.");
  bool finite = true, differs = false;
  const std::vector<float> noisy = rgbPlanes(a, "");
  for (std::size_t i = 0; i < rgb.size(); ++i) finite = finite && std::isfinite(rgb[i]), differs = differs || rgb[i] != noisy[i];
  CHECK(finite);
  CHECK(differs);
}

// The reference is montecl's own 2048-spp render with another seed (its noise is 1/128 of the
// 16-spp variance). The error is over the pixels that neither see the light (reference below 1 in
// every channel) nor touch one that does: at 64x64 the few pixels on the emitter's edge, partly
// covering a source 17 times brighter than anything else, dominate every RMSE, noisy or denoised
// alike (their footprint noise is in the emission added back), and their neighbours take some of
// it through the filter. Measured with the default sampler's one sequence per pixel (2026-12-07,
// seeds 0, 3, 5): noisy 0.00236-0.00249, denoised 0.00179-0.00185, factors 1.32-1.36 (without the
// rim excluded 1.22: the edge's neighbours; with the old 4 sub-sequences, 2026-12-02, 1.55); the
// test asks for 1.25.
// Over the whole image the denoised error must not exceed the noisy one: what is left there is the
// light's edge pixels, whose footprint noise is in the emission added back, not denoised (measured
// 2026-12-03: noisy 0.03187, denoised 0.0318; before the emission was taken out, 0.0864).
constexpr double kWholeImageFactor = 1.0;
TEST_CASE("denoise: a 16-spp Cornell box denoised is closer to a 2048-spp reference than the noisy one" *
          doctest::test_suite("cli shared-scenes")) {
  MCL_SKIP_UNLESS_OIDN();
  const std::string scene = sharedScenes() + "/cornell-box/scene.json";
  MCL_SKIP_UNLESS(std::ifstream(scene).good(), "no shared scenes at " << sharedScenes());
  TempDir dir;
  const std::vector<std::string> base = {"render", scene, "--width", "64", "--height", "64", "--integrator",
                                         "direct", "-q"};
  std::vector<std::string> noisy = base, ref = base;
  noisy.insert(noisy.end(), {"--spp", "16", "--seed", "0", "--denoise", "-o", dir.file("noisy.exr")});
  ref.insert(ref.end(), {"--spp", "2048", "--seed", "1", "-o", dir.file("ref.exr")});
  CliResult n = runMontecl(noisy), r = runMontecl(ref);
  INFO(n.err << r.err);
  REQUIRE(n.exitCode == 0);
  REQUIRE(r.exitCode == 0);
  const LayeredImage img = readLayeredImage(dir.file("noisy.exr")), refImg = readLayeredImage(dir.file("ref.exr"));
  const std::vector<float> reference = rgbPlanes(refImg, ""), plain = rgbPlanes(img, ""),
                           denoised = rgbPlanes(img, "denoised.");
  const std::size_t pixels = img.pixelCount();
  const int width = 64, height = 64;
  REQUIRE(pixels == std::size_t(width * height));
  const auto onLight = [&](int x, int y) {
    const std::size_t p = std::size_t(y) * width + x;
    return reference[p] >= 1.0f || reference[pixels + p] >= 1.0f || reference[2 * pixels + p] >= 1.0f;
  };
  std::vector<float> a, b, c;  // reference, noisy, denoised over the pixels off the light and its rim
  for (std::size_t p = 0; p < pixels; ++p) {
    const int x = int(p % width), y = int(p / width);
    bool nearLight = false;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        nearLight = nearLight || (x + dx >= 0 && x + dx < width && y + dy >= 0 && y + dy < height && onLight(x + dx, y + dy));
    if (nearLight) continue;
    for (int ch = 0; ch < 3; ++ch) {
      a.push_back(reference[ch * pixels + p]);
      b.push_back(plain[ch * pixels + p]);
      c.push_back(denoised[ch * pixels + p]);
    }
  }
  REQUIRE(a.size() > 3 * pixels * 9 / 10);  // the light covers under a tenth of the image
  const double noisyError = rmse(b, a), denoisedError = rmse(c, a);
  MESSAGE("RMSE off the light: noisy " << noisyError << ", denoised " << denoisedError << ", factor "
                                       << noisyError / denoisedError);
  CHECK(noisyError > 1.25 * denoisedError);
  // The whole image, the light's own pixels included: the emission seen directly is added back
  // after the filter, not denoised, so its exact pixels stay exact.
  const double noisyAll = rmse(plain, reference), denoisedAll = rmse(denoised, reference);
  MESSAGE("RMSE over the whole image: noisy " << noisyAll << ", denoised " << denoisedAll << ", factor "
                                              << noisyAll / denoisedAll);
  CHECK(noisyAll > kWholeImageFactor * denoisedAll);
}

TEST_CASE("denoise: render.denoise in the scene file is a boolean; anything else is one line, exit 2" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string obj = std::string(MONTECL_SOURCE_DIR) + "/scenes/demo/demo.obj";
  auto sceneWith = [&](const std::string& value) {
    return "{\"camera\": {\"position\": [0, 1.6, 5], \"target\": [0, 0.5, 0], \"up\": [0, 1, 0], \"fov_y\": 40, "
           "\"width\": 8, \"height\": 8}, \"meshes\": [{\"file\": \"" + obj + "\"}], \"render\": {\"spp\": 1, "
           "\"denoise\": " + value + "}}";
  };
  dir.write("bad.json", sceneWith("1"));
  CliResult bad = runMontecl({"render", dir.file("bad.json"), "-o", dir.file("bad.png"), "-q"});
  CHECK(bad.exitCode == 2);
  CHECK(bad.err.find("render.denoise") != std::string::npos);
  CHECK(bad.err.find("true or false") != std::string::npos);
  // true asks for the denoiser: with the library missing that is the set-up line, exit 2.
  dir.write("on.json", sceneWith("true"));
  CliResult on = runMontecl({"render", dir.file("on.json"), "-o", dir.file("on.png"), "-q"},
                            {"MONTECL_OIDN_LIBRARY=" + dir.file("missing.so")});
  CHECK(on.exitCode == 2);
  CHECK(on.err.find("scripts/setup.sh --oidn") != std::string::npos);
  CHECK(!std::ifstream(dir.file("bad.png")).good());
  CHECK(!std::ifstream(dir.file("on.png")).good());
}

TEST_CASE("denoise: merge combines a denoised and a plain part and leaves the denoised layers out" *
          doctest::test_suite("cli")) {
  MCL_SKIP_UNLESS_OIDN();
  TempDir dir;
  std::vector<std::string> a = demoRenderArgs(dir.file("a.exr"), 2, 0), b = demoRenderArgs(dir.file("b.exr"), 2, 2);
  a.push_back("--denoise");
  REQUIRE(runMontecl(a).exitCode == 0);
  REQUIRE(runMontecl(b).exitCode == 0);
  CliResult m = runMontecl({"merge", dir.file("a.exr"), dir.file("b.exr"), "-o", dir.file("m.exr")});
  INFO(m.err);
  REQUIRE(m.exitCode == 0);  // --denoise is not in the provenance: the parts are one estimate
  CHECK(m.err.find("does not denoise") != std::string::npos);
  const LayeredImage merged = readLayeredImage(dir.file("m.exr")), plain = readLayeredImage(dir.file("b.exr"));
  CHECK(merged.channels.size() == plain.channels.size());
  for (const std::string& ch : merged.channels) CHECK(ch.rfind("denoised.", 0) != 0);
}

}  // namespace test_file_denoise
