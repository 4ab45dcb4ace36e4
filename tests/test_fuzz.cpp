// test_fuzz.cpp: the in-suite fuzz run of every input loader (fuzz/fuzz_entries.h): the seeds and
// then seeded mutants of them (tests/fixtures/mutator.h), in process, at least 10,000 inputs per
// loader. Each input must end in success or the loader's InputError/RuntimeError within 2 s of CPU; any
// other exception or a slow input fails the case, and a hung input (30 s) ends the process. The
// failing inputs are saved to fuzz-findings/<loader>-<n>.bin in the working folder (the build
// folder under CTest); replay one with build-asan/fuzz_<loader> <file> or this case.
// MONTECL_FUZZ_INPUTS raises the input count, MONTECL_FUZZ_SEED the mutator's seed.
#include <doctest/doctest.h>

#include <cxxabi.h>

#include <ctime>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>
#include <typeinfo>

#include "fuzz_entries.h"
#include "mutator.h"

namespace test_file_fuzz {  // keeps this file's helpers apart in a unity batch

namespace {

using montecl_fuzz::Loader;
using montecl_fuzz::Outcome;
using Clock = std::chrono::steady_clock;

constexpr double kMaxSecondsPerInput = 2.0;  // of the process's CPU time (processCpuSeconds)
constexpr int kHangSeconds = 30;

// CPU seconds of the whole process (every thread): what one input costs, however busy the machine.
// On a shared CI machine an input's wall time also counts the time the scheduler gave other jobs
// (a 0.05 s input took 2.3 s of wall time at a load of 5 on 2 cores).
double processCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

long envOr(const char* name, long fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtol(v, nullptr, 10) : fallback;
}

std::string saveFinding(Loader l, std::size_t index, const std::string& input) {
  std::filesystem::create_directories("fuzz-findings");
  std::string path = std::string("fuzz-findings/") + montecl_fuzz::loaderName(l) + "-" + std::to_string(index) + ".bin";
  std::ofstream(path, std::ios::binary) << input;
  return std::filesystem::absolute(path).string();
}

std::string typeName(const std::type_info& t) {
  int status = 0;
  char* name = abi::__cxa_demangle(t.name(), nullptr, nullptr, &status);
  std::string s = status == 0 && name ? name : t.name();
  std::free(name);
  return s;
}

// Ends the process when one input runs longer than kHangSeconds, after saving it.
class Watchdog {
 public:
  explicit Watchdog(Loader l) : loader_(l), thread_([this] { watch(); }) {}
  ~Watchdog() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  void start(std::size_t index, const std::string& input) {
    std::lock_guard<std::mutex> lock(m_);
    index_ = index;
    input_ = &input;
    started_ = Clock::now();
    busy_ = true;
  }
  void finish() {
    std::lock_guard<std::mutex> lock(m_);
    busy_ = false;
  }

 private:
  void watch() {
    std::unique_lock<std::mutex> lock(m_);
    while (!stop_) {
      cv_.wait_for(lock, std::chrono::seconds(1));
      if (busy_ && Clock::now() - started_ > std::chrono::seconds(kHangSeconds)) {
        std::string path = saveFinding(loader_, index_, *input_);
        std::fprintf(stderr, "fuzz %s: input %zu hangs (over %d s), saved to %s\n", montecl_fuzz::loaderName(loader_),
                     index_, kHangSeconds, path.c_str());
        std::fflush(stderr);
        std::_Exit(1);
      }
    }
  }
  Loader loader_;
  std::mutex m_;
  std::condition_variable cv_;
  bool stop_ = false, busy_ = false;
  std::size_t index_ = 0;
  const std::string* input_ = nullptr;
  Clock::time_point started_;
  std::thread thread_;
};

void fuzzLoop(Loader l) {
  const long inputs = std::max(envOr("MONTECL_FUZZ_INPUTS", 10000), 10000L);
  const auto seed = static_cast<std::uint64_t>(envOr("MONTECL_FUZZ_SEED", 14));
  const std::vector<std::string> seeds = montecl_fuzz::seedInputs(l);
  REQUIRE(seeds.size() >= 3);
  montecl_test::Mutator mutator(seed * 31 + static_cast<std::uint64_t>(l));
  std::size_t loaded = 0, rejected = 0;
  std::vector<std::string> findings;
  double slowest = 0.0;
  {
    Watchdog watchdog(l);
    for (long i = 0; i < inputs; ++i) {
      const std::size_t index = static_cast<std::size_t>(i);
      const std::string input = index < seeds.size() ? seeds[index] : mutator.mutate(seeds);
      std::string problem;
      watchdog.start(index, input);
      const double t0 = processCpuSeconds();
      try {
        const auto* bytes = reinterpret_cast<const std::uint8_t*>(input.data());
        (montecl_fuzz::runEntry(l, bytes, input.size()) == Outcome::Loaded ? loaded : rejected)++;
      } catch (const std::exception& e) {
        problem = "uncaught " + typeName(typeid(e)) + ": " + e.what();
      } catch (...) {
        problem = "uncaught exception of an unknown type";
      }
      const double seconds = processCpuSeconds() - t0;
      watchdog.finish();
      slowest = std::max(slowest, seconds);
      if (problem.empty() && seconds > kMaxSecondsPerInput) problem = "took " + std::to_string(seconds) + " s of CPU";
      if (!problem.empty()) findings.push_back("input " + std::to_string(index) + " (" + saveFinding(l, index, input) + "): " + problem.substr(0, 300));
    }
  }
  MESSAGE(std::string(montecl_fuzz::loaderName(l)) << ": " << inputs << " inputs (" << seeds.size() << " seeds), " << loaded
                                      << " loaded, " << rejected << " rejected, " << findings.size()
                                      << " findings, slowest " << slowest << " s of CPU");
  std::string list;
  for (std::size_t k = 0; k < findings.size() && k < 10; ++k) list += findings[k] + "\n";
  INFO(list);
  CHECK(findings.empty());
  // The run reached both ends: some inputs load (not everything is rejected up front) and some fail.
  CHECK(loaded > 0);
  CHECK(rejected > 0);
}

}  // namespace

TEST_CASE("fuzz: 10k mutated scene JSON files load or fail with InputError" * doctest::test_suite("cpu slow")) {
  fuzzLoop(Loader::Scene);
}
TEST_CASE("fuzz: 10k mutated OBJ/MTL files load or fail with InputError" * doctest::test_suite("cpu slow")) {
  fuzzLoop(Loader::Obj);
}
TEST_CASE("fuzz: 10k mutated EXR inputs of merge load or fail with InputError" * doctest::test_suite("cpu slow")) {
  fuzzLoop(Loader::Exr);
}
TEST_CASE("fuzz: 10k mutated program-cache entries verify or are refused" * doctest::test_suite("cpu")) {
  fuzzLoop(Loader::Cache);
}
TEST_CASE("fuzz: 10k mutated PLY files (ASCII and binary) load or fail with InputError" * doctest::test_suite("cpu slow")) {
  fuzzLoop(Loader::Ply);
}
TEST_CASE("fuzz: 10k mutated glTF files (.gltf and .glb) load or fail with InputError" * doctest::test_suite("cpu slow")) {
  fuzzLoop(Loader::Gltf);
}
TEST_CASE("fuzz: 10k mutated pbrt-v4 files load or fail with InputError" * doctest::test_suite("cpu slow")) {
  fuzzLoop(Loader::Pbrt);
}
TEST_CASE("fuzz: 10k mutated Mitsuba XML files load or fail with InputError" * doctest::test_suite("cpu slow")) {
  fuzzLoop(Loader::Mitsuba);
}

}  // namespace test_file_fuzz
