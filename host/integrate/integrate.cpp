// integrate.cpp: integrand descriptions and exact values, the double-precision summaries of the
// per-sample terms, and the OpenCL side (integrate.cl built through the program cache).
#include "integrate/integrate.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cl/cl_errors.h"
#include "cl/cl_session.h"
#include "cl/kernel_source.h"
#include "cl/program_cache.h"
#include "util/errors.h"

namespace montecl {

const char* integrandName(Integrand i) { return i == Integrand::Sine ? "sine" : "smooth2d"; }

const char* estimatorName(Estimator e) {
  switch (e) {
    case Estimator::Rectangle: return "rectangle";
    case Estimator::McUniform: return "mc-uniform";
    case Estimator::McImportance: return "mc-importance";
  }
  return "?";
}

std::string integrandFormula(Integrand i, std::uint32_t k) {
  if (i == Integrand::Sine)
    return "f(x) = 1 + cos(2 pi k x), k = " + std::to_string(k) + ", on [0, 1]; importance pdf 1 + 0.8 cos(2 pi k x)";
  return "f(x, y) = exp(1.5 x) (1 + y + y^2) + 3 exp(-((x - 0.7)^2 + (y - 0.3)^2) / 0.08) on [-0.1, 1.2]^2; "
         "importance pdf (0.6 + 3.75 x)(0.85 + 2.1 y) / Z";
}

int integrandDimensions(Integrand i) { return i == Integrand::Sine ? 1 : 2; }

double smooth2dF(double x, double y) {
  double dx = x - 0.7, dy = y - 0.3;
  return std::exp(1.5 * x) * (1.0 + y + y * y) + 3.0 * std::exp(-(dx * dx + dy * dy) / 0.08);
}

double exactIntegral(Integrand i) {
  if (i == Integrand::Sine) return 1.0;
  const double lo = -0.1, hi = 1.2, s = 0.08;
  auto poly = [](double y) { return y + y * y / 2.0 + y * y * y / 3.0; };
  double smooth = (std::exp(1.5 * hi) - std::exp(1.5 * lo)) / 1.5 * (poly(hi) - poly(lo));
  auto gauss = [&](double mu) {
    return std::sqrt(M_PI * s) / 2.0 * (std::erf((hi - mu) / std::sqrt(s)) - std::erf((lo - mu) / std::sqrt(s)));
  };
  return smooth + 3.0 * gauss(0.7) * gauss(0.3);
}

void rectangleGrid(Integrand i, std::uint32_t n, std::uint32_t& gridX, std::uint32_t& gridY) {
  if (integrandDimensions(i) == 1) {
    gridX = n;
    gridY = 1;
    return;
  }
  gridX = std::max<std::uint32_t>(1, static_cast<std::uint32_t>(std::floor(std::sqrt(double(n)))));
  while (std::uint64_t(gridX + 1) * (gridX + 1) <= n) ++gridX;  // guard sqrt rounding
  while (std::uint64_t(gridX) * gridX > n) --gridX;
  gridY = std::max<std::uint32_t>(1, n / gridX);
}

void summariseTerms(const std::vector<float>& terms, double exact, bool stochastic, Estimate& e) {
  e.n = static_cast<std::uint32_t>(terms.size());
  double sum = 0.0;
  for (float t : terms) sum += t;
  double mean = terms.empty() ? 0.0 : sum / double(terms.size());
  double m2 = 0.0;
  for (float t : terms) m2 += (t - mean) * (t - mean);
  e.estimate = mean;
  e.error = mean - exact;
  e.termVariance = (stochastic && terms.size() > 1) ? m2 / double(terms.size() - 1) : 0.0;
  e.stdDev = terms.empty() ? 0.0 : std::sqrt(e.termVariance / double(terms.size()));
}

RunSpread spreadOf(const std::vector<Estimate>& runs, double exact) {
  RunSpread s;
  s.runs = static_cast<int>(runs.size());
  if (runs.empty()) return s;
  double sum = 0.0, varSum = 0.0, sigmaSum = 0.0;
  for (const Estimate& e : runs) {
    sum += e.estimate;
    varSum += e.stdDev * e.stdDev;
    sigmaSum += e.stdDev;
  }
  double k = double(runs.size());
  s.mean = sum / k;
  s.meanError = s.mean - exact;
  double m2 = 0.0;
  for (const Estimate& e : runs) m2 += (e.estimate - s.mean) * (e.estimate - s.mean);
  s.spread = runs.size() > 1 ? std::sqrt(m2 / (k - 1.0)) : 0.0;
  s.meanStdDev = sigmaSum / k;
  s.stdDevOfMean = std::sqrt(varSum) / k;
  return s;
}

struct IntegralEstimator::Impl {
  DeviceInfo device;
  cl::Context context;
  cl::CommandQueue queue;
  ProgramBuild build;
  cl::Kernel kernel;
};

IntegralEstimator::IntegralEstimator(const DeviceInfo& device) : impl_(std::make_unique<Impl>()) {
  impl_->device = device;
  impl_->context = cl::Context(device.device);
  impl_->queue = cl::CommandQueue(impl_->context, device.device);
  impl_->build = buildProgramCached(impl_->context, device, expandedKernelSource("integrate.cl"), kKernelBuildOptions);
  try {
    impl_->kernel = cl::Kernel(impl_->build.program, "integrate_terms");
  } catch (const cl::Error& e) {
    throw RuntimeError(std::string("kernel integrate_terms: ") + describeClError(e));
  }
}

IntegralEstimator::~IntegralEstimator() = default;

bool IntegralEstimator::programFromCache() const { return impl_->build.fromCache; }
double IntegralEstimator::programBuildMs() const { return impl_->build.buildMs; }

std::vector<float> IntegralEstimator::terms(Integrand i, Estimator e, std::uint32_t n, std::uint32_t gridX,
                                            std::uint32_t seed, std::uint32_t frequency) {
  std::vector<float> out(n);
  if (n == 0) return out;
  cl::Buffer buf(impl_->context, CL_MEM_WRITE_ONLY, std::size_t(n) * sizeof(float));
  cl::Kernel& k = impl_->kernel;
  k.setArg(0, cl_uint(i));
  k.setArg(1, cl_uint(e));
  k.setArg(2, cl_uint(n));
  k.setArg(3, cl_uint(std::max<std::uint32_t>(1, gridX)));
  k.setArg(4, cl_uint(seed));
  k.setArg(5, cl_uint(frequency));
  k.setArg(6, buf);
  std::size_t maxLocal = k.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(impl_->device.device);
  std::size_t local = std::max<std::size_t>(1, std::min<std::size_t>(64, maxLocal));
  std::size_t global = ((std::size_t(n) + local - 1) / local) * local;
  try {
    impl_->queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(global), cl::NDRange(local));
    impl_->queue.enqueueReadBuffer(buf, CL_TRUE, 0, std::size_t(n) * sizeof(float), out.data());
  } catch (const cl::Error& err) {
    throw RuntimeError("kernel integrate_terms: " + describeClError(err));
  }
  return out;
}

Estimate IntegralEstimator::estimate(Integrand i, Estimator e, std::uint32_t n, std::uint32_t seed,
                                     std::uint32_t frequency) {
  if (n == 0) throw InputError("integrate: --n: the sample count must be at least 1");
  Estimate r;
  r.integrand = i;
  r.estimator = e;
  r.frequency = i == Integrand::Sine ? (frequency ? frequency : defaultFrequency(n)) : 0;
  bool stochastic = e != Estimator::Rectangle;
  r.seed = stochastic ? seed : 0;
  std::uint32_t gridX = 1, gridY = 1, used = n;
  if (!stochastic) {
    rectangleGrid(i, n, gridX, gridY);
    used = gridX * gridY;
    r.gridX = gridX;
    r.gridY = gridY;
  }
  summariseTerms(terms(i, e, used, gridX, r.seed, r.frequency), exactIntegral(i), stochastic, r);
  return r;
}

}  // namespace montecl
