// test_integrate.cpp: `montecl integrate` and its estimators: the exact 2D integral against a fine
// host quadrature, the shared integrand code (float, kernel) against the double reference, the
// inverse-CDF samplers, Monte Carlo errors consistent with their estimated std devs (per run and
// across 256 runs), the rectangle rule's aliasing error on the sine, importance sampling's lower
// variance, and the real command line.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>

#include "cl/devices.h"
#include "cli_runner.h"
#include "integrate/integrate.h"
#include "kernels/shared/integrands.h"
#include "stats.h"

namespace test_file_integrate {  // keeps this file's helpers apart in a unity batch

using namespace montecl;

namespace {

IntegralEstimator& estimator() {
  static std::unique_ptr<IntegralEstimator> e = std::make_unique<IntegralEstimator>(selectDevice(""));
  return *e;
}

// Composite Simpson rule in double over [a, b]^2 with m (even) intervals per axis.
template <typename F>
double simpson2d(F f, double a, double b, int m) {
  double h = (b - a) / m, sum = 0.0;
  auto w = [m](int i) { return (i == 0 || i == m) ? 1.0 : (i % 2 ? 4.0 : 2.0); };
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= m; ++j) sum += w(i) * w(j) * f(a + i * h, a + j * h);
  return sum * h * h / 9.0;
}

}  // namespace

TEST_CASE("integrate: smooth2d's exact value matches a fine host quadrature" * doctest::test_suite("cpu")) {
  double quad = simpson2d(smooth2dF, -0.1, 1.2, 1200);
  double exact = exactIntegral(Integrand::Smooth2d);
  INFO("exact " << exact << " quadrature " << quad);
  CHECK(std::abs(exact - quad) < 1e-9 * exact);
  CHECK(exact > 9.0);
  CHECK(exact < 10.5);
  // the sine: 1 + cos(2 pi k x) integrates to 1 for integer k (fine Simpson in 1D)
  for (int k : {1, 3, 64}) {
    int m = 20000;
    double h = 1.0 / m, sum = 0.0;
    for (int i = 0; i <= m; ++i)
      sum += ((i == 0 || i == m) ? 1.0 : (i % 2 ? 4.0 : 2.0)) * (1.0 + std::cos(2.0 * M_PI * k * i * h));
    CHECK(std::abs(sum * h / 3.0 - exactIntegral(Integrand::Sine)) < 1e-9);
  }
}

TEST_CASE("integrate: the shared float integrand matches the double reference" * doctest::test_suite("cpu")) {
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) {
      double x = -0.1 + 1.3 * i / 20.0, y = -0.1 + 1.3 * j / 20.0;
      CHECK(std::abs(mcl_smooth2d_f(float(x), float(y)) - smooth2dF(x, y)) < 1e-5 * smooth2dF(x, y));
    }
}

TEST_CASE("integrate: the importance samplers invert their CDFs" * doctest::test_suite("cpu")) {
  for (int i = 0; i <= 100; ++i) {
    float u = std::min(0.999999f, i / 100.0f);
    float t = mcl_sine_sample_phase(u);
    double cdf = t + 0.8 * std::sin(2.0 * M_PI * t) / (2.0 * M_PI);
    CHECK(std::abs(cdf - u) < 2e-6);
    for (int axis = 0; axis < 2; ++axis) {
      double a = axis ? MCL_S2D_AY : MCL_S2D_AX, b = axis ? MCL_S2D_BY : MCL_S2D_BX;
      float x = mcl_linear_sample(float(a), float(b), u);
      double z = a * 1.3 + 0.5 * b * (1.2 * 1.2 - 0.01);
      double lc = (a * (x + 0.1) + 0.5 * b * (double(x) * x - 0.01)) / z;
      CHECK(std::abs(lc - u) < 5e-6);
    }
  }
  // the pdfs are normalised
  double sumSine = 0.0, sumLin = 0.0;
  for (int i = 0; i < 100000; ++i) {
    float t = (i + 0.5f) / 100000.0f;
    sumSine += mcl_sine_pdf(t);
    sumLin += mcl_linear_pdf(MCL_S2D_AX, MCL_S2D_BX, -0.1f + 1.3f * t);
  }
  CHECK(sumSine / 100000.0 == doctest::Approx(1.0).epsilon(1e-5));
  CHECK(sumLin * 1.3 / 100000.0 == doctest::Approx(1.0).epsilon(1e-5));
}

TEST_CASE("integrate: the kernel computes the same terms as the shared host code" * doctest::test_suite("opencl")) {
  for (Integrand in : {Integrand::Sine, Integrand::Smooth2d})
    for (Estimator e : {Estimator::Rectangle, Estimator::McUniform, Estimator::McImportance}) {
      std::uint32_t n = 1024, gx = in == Integrand::Smooth2d && e == Estimator::Rectangle ? 32 : 1;
      std::vector<float> dev = estimator().terms(in, e, n, gx, 7, 1000);
      REQUIRE(dev.size() == n);
      for (std::uint32_t i = 0; i < n; ++i) {
        float host = mcl_integrate_term(std::uint32_t(in), std::uint32_t(e), i, n, gx, 7, 1000);
        INFO(integrandName(in) << " " << estimatorName(e) << " i=" << i);
        REQUIRE(std::abs(dev[i] - host) <= 1e-4f * std::max(1.0f, std::abs(host)));
      }
    }
}

TEST_CASE("integrate: Monte Carlo errors agree with their estimated standard deviations" * doctest::test_suite("opencl")) {
  const int runs = 256;
  for (Integrand in : {Integrand::Sine, Integrand::Smooth2d})
    for (Estimator e : {Estimator::McUniform, Estimator::McImportance}) {
      std::vector<Estimate> results;
      for (int run = 0; run < runs; ++run) {
        Estimate r = estimator().estimate(in, e, 4096, std::uint32_t(run));
        INFO(integrandName(in) << " " << estimatorName(e) << " run " << run << ": error " << r.error << " sigma "
                               << r.stdDev);
        REQUIRE(r.stdDev > 0.0);
        CHECK(std::abs(r.error) < 4.0 * r.stdDev);
        results.push_back(r);
      }
      RunSpread s = spreadOf(results, exactIntegral(in));
      INFO(integrandName(in) << " " << estimatorName(e) << ": spread " << s.spread << " mean sigma " << s.meanStdDev
                             << " mean error " << s.meanError << " sigma of mean " << s.stdDevOfMean);
      // 256 runs: the spread's relative standard error is about 1 / sqrt(510) = 4.4%
      CHECK(s.spread == doctest::Approx(s.meanStdDev).epsilon(0.2));
      CHECK(std::abs(s.meanError) < 4.0 * s.stdDevOfMean);
      // different seeds give different estimates
      CHECK(results[0].estimate != results[1].estimate);
    }
}

TEST_CASE("integrate: the rectangle rule aliases on the sine; MC does not" * doctest::test_suite("opencl")) {
  const std::uint32_t n = 4096;
  Estimate rect = estimator().estimate(Integrand::Sine, Estimator::Rectangle, n, 0);
  Estimate mc = estimator().estimate(Integrand::Sine, Estimator::McUniform, n, 0);
  INFO("rectangle error " << rect.error << ", MC sigma " << mc.stdDev);
  CHECK(rect.frequency == n);
  CHECK(rect.stdDev == 0.0);
  CHECK(std::abs(rect.error) > 0.9);  // every midpoint at phase 1/2: f = 0 there
  CHECK(rect.estimate < 1e-6);        // ... so every box underestimates
  CHECK(std::abs(rect.error) > 10.0 * mc.stdDev);
  CHECK(std::abs(rect.error) > 10.0 * std::abs(mc.error));
  // the same N with a frequency below Nyquist (k = N/4) integrates exactly
  Estimate slow = estimator().estimate(Integrand::Sine, Estimator::Rectangle, n, 0, n / 4);
  CHECK(std::abs(slow.error) < 1e-5);
  // k = 2N: every midpoint at phase 0, f = 2 there: the estimate is 2
  Estimate near = estimator().estimate(Integrand::Sine, Estimator::Rectangle, n, 0, 2 * n);
  CHECK(std::abs(near.error) > 0.9);
}

TEST_CASE("integrate: importance sampling has lower variance than uniform Monte Carlo" * doctest::test_suite("opencl")) {
  for (Integrand in : {Integrand::Sine, Integrand::Smooth2d}) {
    Estimate uni = estimator().estimate(in, Estimator::McUniform, 4096, 3);
    Estimate imp = estimator().estimate(in, Estimator::McImportance, 4096, 3);
    INFO(integrandName(in) << ": uniform variance " << uni.termVariance << ", importance " << imp.termVariance);
    CHECK(imp.termVariance < 0.5 * uni.termVariance);
    CHECK(imp.stdDev < uni.stdDev);
  }
}

TEST_CASE("integrate: 2D rectangle grid and its small error on the smooth function" * doctest::test_suite("opencl")) {
  std::uint32_t gx = 0, gy = 0;
  rectangleGrid(Integrand::Smooth2d, 4096, gx, gy);
  CHECK(gx == 64);
  CHECK(gy == 64);
  rectangleGrid(Integrand::Smooth2d, 170, gx, gy);
  CHECK(gx == 13);
  CHECK(gy == 13);
  Estimate rect = estimator().estimate(Integrand::Smooth2d, Estimator::Rectangle, 4096, 0);
  CHECK(rect.n == 4096);
  CHECK(std::abs(rect.error) < 1e-2);  // smooth integrand: O(h^2), h = 1.3 / 64
  Estimate coarse = estimator().estimate(Integrand::Smooth2d, Estimator::Rectangle, 169, 0);
  CHECK(std::abs(coarse.error) > std::abs(rect.error));
}

TEST_CASE("integrate: summaries of terms in double" * doctest::test_suite("cpu")) {
  Estimate e;
  summariseTerms({1.0f, 2.0f, 3.0f, 4.0f}, 2.0, true, e);
  CHECK(e.n == 4);
  CHECK(e.estimate == doctest::Approx(2.5));
  CHECK(e.error == doctest::Approx(0.5));
  CHECK(e.termVariance == doctest::Approx(5.0 / 3.0));
  CHECK(e.stdDev == doctest::Approx(std::sqrt(5.0 / 12.0)));
  summariseTerms({1.0f, 2.0f}, 1.5, false, e);
  CHECK(e.termVariance == 0.0);
  CHECK(e.stdDev == 0.0);
}

TEST_CASE("cli: montecl integrate --runs 4 prints every estimator" * doctest::test_suite("cli")) {
  montecl_test::CliResult r = montecl_test::runMontecl({"integrate", "--runs", "4"});
  INFO("stderr: " << r.err << "\nstdout: " << r.out);
  REQUIRE(r.exitCode == 0);
  for (const char* word : {"sine", "smooth2d", "rectangle", "mc-uniform", "mc-importance", "exact", "avg", "spread",
                           "std.dev", "64x64"})
    CHECK(r.out.find(word) != std::string::npos);
  int runLines = 0;
  for (std::size_t pos = 0; (pos = r.out.find("mc-uniform ", pos)) != std::string::npos; ++pos) ++runLines;
  CHECK(runLines >= 2 * 4);  // four runs for each integrand (plus avg and spread lines)
}

TEST_CASE("cli: montecl integrate --json and bad options" * doctest::test_suite("cli sanitize")) {
  montecl_test::CliResult r = montecl_test::runMontecl({"integrate", "--integrand", "sine", "--n", "1000", "--runs",
                                                        "3", "--json"});
  INFO("stderr: " << r.err);
  REQUIRE(r.exitCode == 0);
  nlohmann::json j = nlohmann::json::parse(r.out);
  REQUIRE(j["integrands"].size() == 1);
  CHECK(j["integrands"][0]["name"] == "sine");
  CHECK(j["integrands"][0]["exact"] == 1.0);
  REQUIRE(j["integrands"][0]["estimators"].size() == 3);
  CHECK(j["integrands"][0]["estimators"][1]["runs"].size() == 3);
  CHECK(j["integrands"][0]["estimators"][0]["runs"][0]["estimate"].get<double>() == doctest::Approx(0.0).epsilon(1e-6));
  CHECK(montecl_test::runMontecl({"integrate", "--integrand", "cosine"}).exitCode == 2);
  CHECK(montecl_test::runMontecl({"integrate", "--n", "0"}).exitCode == 2);
  CHECK(montecl_test::runMontecl({"integrate", "--device", "no-such-device-xyz"}).exitCode == 2);
}

}  // namespace test_file_integrate
