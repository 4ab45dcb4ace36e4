// cmd_integrate.cpp: `montecl integrate`: the lecture's experiment. For each built-in integrand it
// runs the rectangle (midpoint) rule, uniform Monte Carlo and importance sampling with N samples
// on an OpenCL device and prints estimate, error against the exact value and the estimated std
// dev of the estimate; --runs K repeats the Monte Carlo estimators with seeds 0..K-1 and adds
// their average and their spread (std dev across runs). --json prints the same as JSON.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cl/devices.h"
#include "cli/commands.h"
#include "integrate/integrate.h"
#include "util/errors.h"

namespace montecl {
namespace {

struct IntegrateArgs {
  std::uint32_t n = 4096;
  int runs = 1;
  std::uint32_t frequency = 0;
  std::string integrand = "all", device;
  bool json = false, verbose = false;
};

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

int runIntegrate(const IntegrateArgs& a) {
  std::vector<Integrand> integrands;
  if (a.integrand == "sine" || a.integrand == "all") integrands.push_back(Integrand::Sine);
  if (a.integrand == "smooth2d" || a.integrand == "all") integrands.push_back(Integrand::Smooth2d);
  DeviceInfo device = selectOpenClDevice(a.device, "integrate");
  IntegralEstimator est(device);
  if (a.verbose)
    std::cerr << "montecl: device " << deviceIndexString(device) << " " << device.name << "; kernel "
              << (est.programFromCache() ? "loaded from cache" : "compiled") << " in " << est.programBuildMs()
              << " ms\n";

  nlohmann::json jout = {{"n", a.n}, {"runs", a.runs}, {"integrands", nlohmann::json::array()}};
  for (Integrand in : integrands) {
    double exact = exactIntegral(in);
    std::uint32_t k = in == Integrand::Sine ? (a.frequency ? a.frequency : defaultFrequency(a.n)) : 0;
    nlohmann::json jin = {{"name", integrandName(in)}, {"formula", integrandFormula(in, k)}, {"exact", exact},
                          {"estimators", nlohmann::json::array()}};
    if (!a.json) {
      std::printf("%s: %s\n", integrandName(in), integrandFormula(in, k).c_str());
      std::printf("  exact = %.10g\n", exact);
      std::printf("  %-14s %9s %5s %16s %14s %14s\n", "estimator", "N", "run", "estimate", "error", "std.dev");
    }
    for (Estimator e : {Estimator::Rectangle, Estimator::McUniform, Estimator::McImportance}) {
      bool stochastic = e != Estimator::Rectangle;
      int runs = stochastic ? a.runs : 1;
      std::vector<Estimate> results;
      nlohmann::json jruns = nlohmann::json::array();
      for (int run = 0; run < runs; ++run) {
        Estimate r = est.estimate(in, e, a.n, static_cast<std::uint32_t>(run), a.frequency);
        results.push_back(r);
        nlohmann::json jr = {{"estimate", r.estimate}, {"error", r.error}, {"std_dev", r.stdDev}};
        if (stochastic) jr["run"] = run;
        jruns.push_back(jr);
        if (!a.json) {
          std::string nText = std::to_string(r.n);
          if (!stochastic && integrandDimensions(in) == 2)
            nText = std::to_string(r.gridX) + "x" + std::to_string(r.gridY);
          std::printf("  %-14s %9s %5s %16s %14s %14s\n", estimatorName(e), nText.c_str(),
                      stochastic ? std::to_string(run).c_str() : "-", fmt("%.10f", r.estimate).c_str(),
                      fmt("%+.3e", r.error).c_str(),
                      stochastic ? fmt("%.3e", r.stdDev).c_str() : "0 (determ.)");
        }
      }
      nlohmann::json jest = {{"name", estimatorName(e)}, {"n", results.front().n}, {"runs", jruns}};
      if (!stochastic) {
        jest["grid"] = {results.front().gridX, results.front().gridY};
        jest["stochastic"] = false;
      } else {
        jest["stochastic"] = true;
        RunSpread s = spreadOf(results, exact);
        jest["average"] = {{"estimate", s.mean}, {"error", s.meanError}, {"std_dev", s.stdDevOfMean}};
        jest["spread"] = s.spread;
        jest["mean_std_dev"] = s.meanStdDev;
        if (!a.json && runs > 1) {
          std::printf("  %-14s %9s %5s %16s %14s %14s\n", estimatorName(e), std::to_string(results.front().n).c_str(),
                      "avg", fmt("%.10f", s.mean).c_str(), fmt("%+.3e", s.meanError).c_str(),
                      fmt("%.3e", s.stdDevOfMean).c_str());
          std::printf("  %-14s spread across %d runs (std dev of the estimates) %.3e; mean estimated std.dev %.3e\n",
                      estimatorName(e), runs, s.spread, s.meanStdDev);
        }
      }
      jin["estimators"].push_back(jest);
    }
    jout["integrands"].push_back(jin);
    if (!a.json) std::printf("\n");
  }
  if (a.json) std::cout << jout.dump(2) << "\n";
  return kExitOk;
}

}  // namespace

void addIntegrateCommand(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<IntegrateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "integrate", "Rectangle rule vs Monte Carlo vs importance sampling on built-in integrands (OpenCL)");
  cmd->add_option("--n", args->n, "Samples per estimate (2D rectangle rule: floor(sqrt(N)) x N/that grid)")
      ->check(CLI::Range(1u, 1u << 24));
  cmd->add_option("--runs", args->runs, "Repeat the Monte Carlo estimators with seeds 0..K-1")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--integrand", args->integrand, "sine | smooth2d | all")
      ->check(CLI::IsMember({"sine", "smooth2d", "all"}));
  cmd->add_option("--frequency", args->frequency, "Sine frequency k (default: N, where the midpoint rule aliases)")
      ->check(CLI::Range(1u, 1u << 30));
  cmd->add_option("--device", args->device, "OpenCL device: P:D, or part of the device or platform name");
  cmd->add_flag("--json", args->json, "Print the results as JSON");
  cmd->add_flag("-v,--verbose", args->verbose, "Device and kernel build details on stderr");
  cmd->callback([args, &exitCode]() { exitCode = runIntegrate(*args); });
}

}  // namespace montecl
