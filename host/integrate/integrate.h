// integrate.h: the lecture's integration experiment behind `montecl integrate`: the rectangle
// (midpoint) rule, uniform Monte Carlo and importance sampling on built-in integrands
// (kernels/shared/integrands.h), each sample evaluated by an OpenCL kernel (kernels/integrate.cl,
// its own program), summed on the host in double, with the estimate's standard deviation
// estimated from the same samples.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cl/devices.h"

namespace montecl {

enum class Integrand : std::uint32_t { Sine = 0, Smooth2d = 1 };        // MCL_INTEGRAND_*
enum class Estimator : std::uint32_t { Rectangle = 0, McUniform = 1, McImportance = 2 };  // MCL_EST_*

const char* integrandName(Integrand i);  // "sine", "smooth2d"
const char* estimatorName(Estimator e);  // "rectangle", "mc-uniform", "mc-importance"
// One line describing f, its domain and (sine) frequency k.
std::string integrandFormula(Integrand i, std::uint32_t k);
int integrandDimensions(Integrand i);

// Exact integral, in double: sine 1 (any integer k >= 1); smooth2d a closed form with erf.
double exactIntegral(Integrand i);
// smooth2d's f in double (the kernel's float version is mcl_smooth2d_f), for host quadrature.
double smooth2dF(double x, double y);

// The frequency used when the user gives none: k = N, so the midpoint rule aliases completely.
inline std::uint32_t defaultFrequency(std::uint32_t n) { return n; }

// Midpoint grid for n points in d dimensions: 1D n x 1; 2D floor(sqrt(n)) x (n / that).
void rectangleGrid(Integrand i, std::uint32_t n, std::uint32_t& gridX, std::uint32_t& gridY);

struct Estimate {
  Integrand integrand = Integrand::Sine;
  Estimator estimator = Estimator::Rectangle;
  std::uint32_t n = 0;                  // samples actually used (rectangle 2D: gridX * gridY)
  std::uint32_t gridX = 0, gridY = 0;   // rectangle rule only
  std::uint32_t frequency = 0;          // sine only
  std::uint32_t seed = 0;               // run index (Monte Carlo only)
  double estimate = 0.0;                // mean of the terms
  double error = 0.0;                   // estimate - exact
  double termVariance = 0.0;            // unbiased sample variance of one term (0 for rectangle)
  double stdDev = 0.0;                  // estimated std dev of the estimate: sqrt(termVariance / n)
};

// Mean and unbiased variance of the terms (double, two-pass) folded into e (n, estimate, error,
// termVariance, stdDev); a deterministic rule gets termVariance = stdDev = 0.
void summariseTerms(const std::vector<float>& terms, double exact, bool stochastic, Estimate& e);

// Across K runs of one Monte Carlo estimator.
struct RunSpread {
  int runs = 0;
  double mean = 0.0;          // average of the estimates
  double meanError = 0.0;     // mean - exact
  double spread = 0.0;        // std dev of the estimates across runs (n - 1); 0 for one run
  double meanStdDev = 0.0;    // average of the per-run estimated std devs (what spread should match)
  double stdDevOfMean = 0.0;  // estimated std dev of the average: sqrt(sum sigma_i^2) / K
};
RunSpread spreadOf(const std::vector<Estimate>& runs, double exact);

// Owns an OpenCL context, queue and the integrate.cl program on one device.
class IntegralEstimator {
 public:
  explicit IntegralEstimator(const DeviceInfo& device);
  ~IntegralEstimator();
  IntegralEstimator(const IntegralEstimator&) = delete;
  IntegralEstimator& operator=(const IntegralEstimator&) = delete;

  bool programFromCache() const;
  double programBuildMs() const;

  // The n per-sample terms computed on the device (rectangle 2D: n must be gridX * gridY).
  std::vector<float> terms(Integrand i, Estimator e, std::uint32_t n, std::uint32_t gridX, std::uint32_t seed,
                           std::uint32_t frequency);

  // One estimate with n samples (frequency 0: defaultFrequency(n)); seed is ignored by the
  // deterministic rectangle rule. Throws InputError for n == 0.
  Estimate estimate(Integrand i, Estimator e, std::uint32_t n, std::uint32_t seed, std::uint32_t frequency = 0);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace montecl
