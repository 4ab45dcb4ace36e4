// stats.h: small statistics helpers for the tests: chi-square critical values and z-scores.
#pragma once
#include <cmath>

namespace montecl_test {

// Upper critical value of the chi-square distribution with k degrees of freedom at a tail
// probability given by the standard-normal quantile z (z = 3.72 for 1e-4), Wilson-Hilferty.
inline double chiSquareCritical(double k, double z = 3.719) {
  double a = 2.0 / (9.0 * k);
  double c = 1.0 - a + z * std::sqrt(a);
  return k * c * c * c;
}

// Running mean and variance of a stream of samples (Welford), in double.
struct RunningStats {
  double n = 0, mean = 0, m2 = 0;
  void add(double x) {
    n += 1;
    double d = x - mean;
    mean += d / n;
    m2 += d * (x - mean);
  }
  double variance() const { return n > 1 ? m2 / (n - 1) : 0.0; }
  double standardError() const { return std::sqrt(variance() / n); }
};

}  // namespace montecl_test
