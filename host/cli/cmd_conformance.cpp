// cmd_conformance.cpp: `montecl conformance [--json] [--device SPEC]... [--bvh-layout L]`: builds every kernel on
// each OpenCL device (default: all found), renders the conformance set and compares each image
// with the host backend's (conformance/conformance.h). Exit 0 when every device passes, else 1.
#include <iostream>

#include "cli/commands.h"
#include "cli/validators.h"
#include "conformance/conformance.h"
#include "util/errors.h"

namespace montecl {

struct ConformanceArgs {
  ConformanceOptions options;
  std::string bvhLayout = "auto";
  bool json = false;
};

int runConformanceCommand(const ConformanceArgs& a) {
  ConformanceOptions options = a.options;
  options.bvhLayout = parseBvhLayout(a.bvhLayout);
  ConformanceReport report = runConformance(options);
  if (a.json)
    std::cout << conformanceJson(report).dump(2) << std::endl;
  else
    std::cout << conformanceTable(report) << std::flush;
  return report.pass ? kExitOk : kExitRuntime;
}

void addConformanceOptions(CLI::App* cmd, ConformanceArgs& a) {
  cmd->add_option("--size", a.options.set.size, "Width and height of the analytic scenes' images")
      ->check(positiveInteger());
  cmd->add_option("--spp", a.options.set.spp, "Samples per pixel of the analytic scenes")->check(positiveInteger());
  cmd->add_option("--cornell-size", a.options.set.cornellSize, "Width and height of the Cornell box images")
      ->check(positiveInteger());
  cmd->add_option("--cornell-spp", a.options.set.cornellSpp, "Samples per pixel of the Cornell box")
      ->check(positiveInteger());
  cmd->add_option("--cornell", a.options.set.cornellPath,
                  "Cornell box scene.json (default: <source>/../shared/scenes/cornell-box/scene.json)");
}

void addConformanceCommand(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<ConformanceArgs>();
  CLI::App* cmd = app.add_subcommand(
      "conformance", "Render a small test set on each OpenCL device and compare it with the host backend");
  cmd->add_option("--device", args->options.deviceSpecs,
                  "Device to check (repeatable): P:D, part of a name, or host; default: every OpenCL device");
  cmd->add_flag("--json", args->json, "Print the report as JSON");
  cmd->add_option("--bvh-layout", args->bvhLayout,
                  "BVH the OpenCL devices traverse: auto (binary on GPUs, wide otherwise) | wide | binary; "
                  "the host backend and its reference images use wide")
      ->check(CLI::IsMember({"auto", "wide", "binary"}));
  cmd->add_option("--lanes", args->options.lanes,
                  "Items per work item of the OpenCL devices' packet stages: 1 | 4 | 8 | 16 (default: each "
                  "device's, `montecl devices`)")
      ->check(CLI::IsMember({1u, 4u, 8u, 16u}));
  addConformanceOptions(cmd, *args);
  cmd->callback([args, &exitCode]() { exitCode = runConformanceCommand(*args); });
}

}  // namespace montecl
