// cmd_bench.cpp: `montecl bench SCENE [--repeat N] [--json FILE] [--device SPEC] [--threads T]
// [--bvh-layout L]`: runs the traversal benchmark (host/bench/bench.h), prints its table on stdout,
// optionally writes the JSON atomically. Exit 0 when every ray matches the host reference, 1 otherwise.
#include <fstream>
#include <iostream>
#include <limits>

#include "bench/bench.h"
#include "cli/commands.h"
#include "cli/validators.h"
#include "scene/scene.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace montecl {

void addBenchCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<BenchOptions>();
  auto quiet = std::make_shared<bool>(false);
  auto noEmbree = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "bench", "Benchmark BVH build and traversal kernels (primary, AO, shadow rays) against the host "
               "reference and Embree");
  cmd->add_option("scene", o->scene, "Scene file (.json or pbrt-v4 .pbrt) or a bare mesh (.obj, .ply, .gltf, .glb)")->required();
  cmd->add_option("--repeat", o->repeat, "Timed repetitions per kernel (median and minimum reported)")
      ->check(positiveInteger());
  cmd->add_option("--warmup", o->warmup, "Untimed runs before the timed ones")->check(integerIn(0, std::numeric_limits<int>::max(), "a non-negative integer"));
  cmd->add_option("--json", o->jsonPath, "Write every result to this JSON file");
  cmd->add_option("--device", o->device, "OpenCL device: P:D, or part of the device or platform name");
  cmd->add_option("--threads", o->threads, "Embree and host reference threads (default: the device's compute units)")
      ->check(positiveInteger());
  cmd->add_option("--width", o->width, "Override the scene's image width (primary rays = width x height)")
      ->check(positiveInteger(kMaxImageSide));
  cmd->add_option("--height", o->height, "Override the scene's image height")->check(positiveInteger(kMaxImageSide));
  cmd->add_option("--work-group-size", o->workGroupSize, "Kernel work-group size (default: min(64, kernel max))")
      ->check(positiveInteger());
  cmd->add_option("--bvh-layout", o->bvhLayout,
                  "BVH the kernels traverse: auto (binary on GPUs, wide otherwise) | wide | binary")
      ->check(CLI::IsMember({"auto", "wide", "binary"}));
  cmd->add_option("--split-budget", o->splitBudget,
                  "Spatial splits: at most this many extra triangle references per triangle (0: none)")
      ->check(CLI::Range(0.0f, 4.0f));
  cmd->add_flag("--no-embree", *noEmbree, "Skip the Embree comparison");
  cmd->add_flag("--sah-reference", o->sahReference,
                "Also compute the SAH cost of a full-sweep build (slow) and the ratio binned / full sweep");
  cmd->add_flag("-q,--quiet", *quiet, "No progress messages on stderr");
  cmd->callback([o, quiet, noEmbree, &exitCode]() {
    o->embree = !*noEmbree;
    nlohmann::json r = runBench(*o, !*quiet);
    std::cout << formatBenchTable(r) << std::flush;
    if (!o->jsonPath.empty()) {
      writeAtomically(o->jsonPath, [&](const std::string& tmp) {
        std::ofstream out(tmp);
        out << r.dump(2) << "\n";
        out.close();
        if (!out) throw RuntimeError(o->jsonPath + ": write failed");
      });
    }
    exitCode = r["mismatches_total"].get<std::size_t>() == 0 ? kExitOk : kExitRuntime;
  });
}

}  // namespace montecl
