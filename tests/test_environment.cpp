// test_environment.cpp: the environment light's sampling (kernels/shared/environment.h with the
// tables of host/render/environment_table.cpp), compiled as C++: samples pass a chi-square test
// against env_pdf over the map's texels (and fail against the solid-angle-uniform pdf), the pdf
// integrates to one over the sphere, samples carry the radiance that a lookup returns, and
// importance sampling estimates irradiance with lower variance than cosine sampling.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "kernels/shared/environment.h"
#include "kernels/shared/rng.h"
#include "render/environment_table.h"
#include "stats.h"

namespace test_file_environment {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using montecl_test::chiSquareCritical;
using montecl_test::RunningStats;

namespace {

// A 32 x 16 map: dim blue sky above the horizon, dark ground below, one bright "sun" texel block.
std::vector<glm::vec3> skyPixels(int w, int h) {
  std::vector<glm::vec3> rgb(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::vec3 c = y < h / 2 ? glm::vec3(0.2f, 0.3f, 0.6f) : glm::vec3(0.05f, 0.04f, 0.03f);
      if (y >= 3 && y <= 4 && x >= 20 && x <= 21) c = glm::vec3(200.0f, 180.0f, 150.0f);
      if (x == 7 && y == 10) c = glm::vec3(0.0f);  // a black texel: never sampled
      rgb[std::size_t(y) * w + x] = c;
    }
  return rgb;
}

struct Env {
  EnvironmentTable table;
  FrameParams frame{};
};

Env makeEnv(float rotateRadians) {
  Env e;
  e.table = environmentFromPixels(32, 16, skyPixels(32, 16));
  e.frame.environment = float4(1.0f, 1.0f, 1.0f, 1.0f);
  e.frame.envWidth = e.table.width;
  e.frame.envHeight = e.table.height;
  e.frame.envRotateY = rotateRadians;
  return e;
}

}  // namespace

TEST_CASE("environment map samples pass a chi-square test against env_pdf per texel" * doctest::test_suite("cpu")) {
  for (float rot : {0.0f, 1.3f}) {
    Env e = makeEnv(rot);
    const int w = 32, h = 16, count = 400000;
    std::vector<double> observed(std::size_t(w) * h, 0.0);
    int disagree = 0;  // a sample on a texel boundary may look up its neighbour (float rounding)
    for (int i = 0; i < count; ++i) {
      float4 u = rng_uniform4(3u, uint(i), 0u, 0u);
      EnvSample s = env_sample(&e.frame, e.table.map.data(), e.table.cdf.data(), u.x, u.y);
      REQUIRE(s.pdf > 0.0f);
      REQUIRE(std::abs(glm::length(s.wi) - 1.0f) < 1e-5f);
      // The sample's radiance and pdf are what a lookup of its direction returns.
      const float3 looked = env_radiance(&e.frame, e.table.map.data(), s.wi);
      const float pdf = env_pdf(&e.frame, e.table.map.data(), s.wi);
      if (!(looked == s.le && pdf == doctest::Approx(s.pdf).epsilon(1e-3))) ++disagree;
      const float2 uv = env_dir_to_uv(rotate_about_y(s.wi, -rot));
      observed[env_texel(uv, w, h)] += 1.0;
    }
    // Texel (x, y) holds probability density(x, y) / (w h) in uv space.
    double stat = 0.0, wrongStat = 0.0;
    int dof = -1;
    for (int y = 0; y < h; ++y) {
      const double sinTheta = std::sin(M_PI * (y + 0.5) / h);
      for (int x = 0; x < w; ++x) {
        const std::size_t k = std::size_t(y) * w + x;
        const double expected = double(e.table.map[k].w) / (w * h) * count;
        const double uniform = sinTheta * (M_PI / h) * (2.0 * M_PI / w) / (4.0 * M_PI) * count;  // solid angle
        if (expected < 5.0) {
          CHECK(observed[k] <= 5.0 + 10.0 * expected);
          continue;
        }
        stat += (observed[k] - expected) * (observed[k] - expected) / expected;
        wrongStat += (observed[k] - uniform) * (observed[k] - uniform) / uniform;
        ++dof;
      }
    }
    INFO("rotate " << rot << ": chi2 " << stat << " dof " << dof << ", against uniform " << wrongStat);
    CHECK(stat < chiSquareCritical(dof));
    CHECK(wrongStat > chiSquareCritical(dof));
    CHECK(observed[10 * w + 7] == 0.0);  // the black texel
    CHECK(disagree < count / 1000);
  }
}

TEST_CASE("environment pdf integrates to one over the sphere; constant environment is uniform" * doctest::test_suite("cpu")) {
  Env e = makeEnv(0.7f);
  RunningStats integral;
  for (int i = 0; i < 400000; ++i) {  // E[pdf / (1/(4 pi))] over uniform directions
    float4 u = rng_uniform4(4u, uint(i), 0u, 0u);
    const float y = 1.0f - 2.0f * u.y, r = std::sqrt(std::max(0.0f, 1.0f - y * y));
    const float3 d(r * std::cos(2.0f * float(M_PI) * u.x), y, r * std::sin(2.0f * float(M_PI) * u.x));
    integral.add(double(env_pdf(&e.frame, e.table.map.data(), d)) * 4.0 * M_PI);
  }
  INFO("integral " << integral.mean << " +- " << integral.standardError());
  CHECK(std::abs(integral.mean - 1.0) < 4.0 * integral.standardError());
  FrameParams c{};
  c.environment = float4(0.5f, 1.0f, 2.0f, 1.0f);
  EnvSample s = env_sample(&c, nullptr, nullptr, 0.3f, 0.8f);
  CHECK(s.pdf == doctest::Approx(1.0 / (4.0 * M_PI)));
  CHECK(s.le == float3(0.5f, 1.0f, 2.0f));
  CHECK(std::abs(glm::length(s.wi) - 1.0f) < 1e-6f);
}

TEST_CASE("environment importance sampling: same irradiance as cosine sampling, lower variance" * doctest::test_suite("cpu")) {
  Env e = makeEnv(0.0f);
  const float3 n = normalize(float3(0.2f, 1.0f, -0.1f));  // a surface facing up, toward the sun
  RunningStats importance, cosine;
  for (int i = 0; i < 200000; ++i) {
    float4 u = rng_uniform4(8u, uint(i), 0u, 0u);
    EnvSample s = env_sample(&e.frame, e.table.map.data(), e.table.cdf.data(), u.x, u.y);
    const float c = dot(n, s.wi);
    importance.add(c > 0.0f ? double(luminance(s.le)) * c / s.pdf : 0.0);
    const float3 wi = to_world(sample_cosine_hemisphere(u.z, u.w), n);
    cosine.add(double(luminance(env_radiance(&e.frame, e.table.map.data(), wi))) * M_PI);  // L cos / (cos/pi)
  }
  const double se = std::hypot(importance.standardError(), cosine.standardError());
  INFO("importance " << importance.mean << " var " << importance.variance() << "; cosine " << cosine.mean << " var "
                     << cosine.variance());
  CHECK(std::abs(importance.mean - cosine.mean) < 4.0 * se);
  CHECK(importance.variance() < 0.1 * cosine.variance());
}

TEST_CASE("mcl_sincos_turns: sine and cosine of 2 pi t within 1e-7 of the library's" * doctest::test_suite("cpu")) {
  double worst = 0.0;
  for (int i = -4000; i <= 8000; ++i) {
    const float t = float(i) / 4000.0f + 1e-4f * float(i % 7);
    float s = 0.0f, c = 0.0f;
    mcl_sincos_turns(t, &s, &c);
    worst = std::max({worst, std::abs(double(s) - std::sin(2.0 * M_PI * double(t))),
                      std::abs(double(c) - std::cos(2.0 * M_PI * double(t)))});
  }
  CHECK(worst < 2e-7);
}

TEST_CASE("mcl_atan2 and mcl_acos: within 5e-7 rad (2 float ulps at pi) of the library's, signed zeros as IEEE's atan2" * doctest::test_suite("cpu")) {
  double worstAtan = 0.0, worstAcos = 0.0;
  for (int i = -300; i <= 300; ++i)
    for (int j = -300; j <= 300; ++j) {
      const float y = float(i) / 97.0f, x = float(j) / 89.0f;  // every octant, the axes and the origin
      worstAtan = std::max(worstAtan, std::abs(double(mcl_atan2(y, x)) - std::atan2(double(y), double(x))));
    }
  for (int i = -20000; i <= 20000; ++i) {
    const float x = float(i) / 20000.0f;
    worstAcos = std::max(worstAcos, std::abs(double(mcl_acos(x)) - std::acos(double(x))));
  }
  CHECK(worstAtan < 5e-7);  // float32 rounds results near pi to 2.4e-7
  CHECK(worstAcos < 5e-7);
  // The map's seam and poles: atan2(+-0, -0) = +-pi and atan2(+-0, +0) = +-0, as the library's.
  for (float y : {0.0f, -0.0f})
    for (float x : {0.0f, -0.0f, 1.0f, -1.0f}) {
      INFO("y " << y << " x " << x);
      CHECK(mcl_atan2(y, x) == float(std::atan2(y, x)));
      CHECK(std::signbit(mcl_atan2(y, x)) == std::signbit(std::atan2(y, x)));
    }
}

}  // namespace test_file_environment
