// bench.cpp: the body of `montecl bench`. Steps: load the scene, build the BVH (build ms, nodes,
// bytes per triangle, SAH cost), generate the seeded ray sets with host references (ray_sets.h),
// time the `intersect` (closest hit: primary, diffuse bounce) and `intersect_shadow` (any hit: AO, shadow) kernels
// with profiling events (warm-up + N repetitions, median and minimum), count mismatches against the
// reference, then build and trace the same on Embree 3 and compute montecl/Embree ratios.
//
// JSON (all times in ms, throughput in Mrays/s, computed from the median time):
// {"scene", "device", "platform", "driver_version", "compute_units", "cpu_model", "threads",
//  "width", "height", "triangles", "emitters", "repeat", "rel_tolerance", "embree_version",
//  "bvh": {"layout" (wide | binary), "build_ms" (binary_build_ms + collapse_ms: the 8-wide collapse,
//          0 for the binary layout), "binary_build_ms", "collapse_ms", "nodes", "depth", "sah_cost", "bytes",
//          "bytes_per_triangle", "node_bytes_per_triangle"} (bytes: the traversed layout's),
//          with --sah-reference also "sweep_sah_cost" and "sah_ratio" (binned / full sweep)},
//  "embree": {"build_ms"}, "build_ratio" (montecl ms / Embree ms),
//  "rays": [{"kind" (primary | ao | shadow | bounce: the "diffuse bounce" set), "query", "count", "hits", "median_ms", "min_ms", "mrays_per_s",
//            "best_mrays_per_s", "embree_median_ms", "embree_min_ms", "embree_mrays_per_s",
//            "ratio" (montecl / Embree Mrays/s), "mismatches", "embree_mismatches",
//            "host_ref_mrays_per_s" (the same traversal code compiled for the host, on T threads, one run)}],
//  "peak_rss_mb", "mismatches_total"}
#include "bench/bench.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "bench/bench_alpha.h"
#include "bench/embree_tracer.h"
#include "bench/ray_sets.h"
#include "bvh/bvh_visit_counts.h"
#include "bvh/bvh.h"
#include "scene/scene_instances.h"
#include "util/host_memory.h"
#include "bvh/sah_reference.h"
#include "render/ray_tracer.h"
#include "render/stage_program.h"
#include "cl/cl_errors.h"
#include "cl/cl_session.h"
#include "cl/devices.h"
#include "util/errors.h"

namespace montecl {
namespace {

using nlohmann::json;

struct Timing {
  double medianMs = 0.0, minMs = 0.0;
};

Timing summarize(std::vector<double> ms) {
  Timing t;
  if (ms.empty()) return t;
  std::sort(ms.begin(), ms.end());
  std::size_t n = ms.size();
  t.medianMs = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
  t.minMs = ms.front();
  return t;
}

double peakRssMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      auto p = line.find(':');
      if (p != std::string::npos) return line.substr(line.find_first_not_of(" \t", p + 1));
    }
  return "unknown";
}

// Runs one ray set through the device kernel warmup + repeat times; times the last `repeat` runs
// (profiling events) and fills t (closest hit distance, INFINITY on a miss) or occ.
Timing timeOnDevice(RayTracer& tracer, const RaySet& set, int warmup, int repeat, std::vector<float>& t,
                    std::vector<std::uint8_t>& occ) {
  std::vector<double> ms;
  if (set.query == RayKind::Closest) {
    std::vector<Hit> hits = tracer.closest(set.rays, warmup + repeat, &ms);
    t.resize(hits.size());
    for (std::size_t i = 0; i < hits.size(); ++i) t[i] = hits[i].tri == MCL_NO_HIT ? INFINITY : hits[i].t;
  } else {
    std::vector<int> o = tracer.occluded(set.rays, warmup + repeat, &ms);
    occ.assign(o.begin(), o.end());
  }
  ms.erase(ms.begin(), ms.begin() + std::min<std::size_t>(std::size_t(warmup), ms.size()));
  return summarize(ms);
}

bool closestMismatch(float ref, float got, double tol) {
  bool rh = std::isfinite(ref), gh = std::isfinite(got);
  if (rh != gh) return true;
  return rh && std::fabs(double(got) - double(ref)) > tol * double(ref);
}

std::size_t countMismatches(const RaySet& set, const std::vector<float>& t, const std::vector<std::uint8_t>& occ,
                            double tol) {
  std::size_t n = 0;
  if (set.query == RayKind::Closest) {
    for (std::size_t i = 0; i < set.rays.size(); ++i) n += closestMismatch(set.refT[i], t[i], tol);
  } else {
    for (std::size_t i = 0; i < set.rays.size(); ++i) n += (set.refOccluded[i] != 0) != (occ[i] != 0);
  }
  return n;
}

double mrays(std::size_t count, double ms) { return ms > 0.0 ? double(count) / (ms * 1e3) : 0.0; }

void checkJsonPath(const std::string& path) {
  if (path.empty()) return;
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (!dir.empty() && !std::filesystem::is_directory(dir))
    throwInputError(path, "", "output folder '" + dir.string() + "' does not exist");
}

}  // namespace

json runBench(const BenchOptions& o, bool verbose) {
  if (o.repeat < 1) throwInputError(o.scene, "", "--repeat must be at least 1");
  checkJsonPath(o.jsonPath);
  std::vector<std::string> warnings;
  Scene scene = loadScene(o.scene, warnings);
  for (const std::string& w : warnings) std::cerr << "montecl: warning: " << w << "\n";
  if (o.width) scene.camera.width = *o.width;
  if (o.height) scene.camera.height = *o.height;
  if (scene.triangles.empty()) throwInputError(o.scene, "", "the scene has no triangles");
  DeviceInfo device = selectOpenClDevice(o.device, "bench");
  BvhLayout layout = resolveStageLayout(parseBvhLayout(o.bvhLayout), device);
  unsigned threads = o.threads ? o.threads : std::max(1u, device.computeUnits);
  auto say = [&](const std::string& s) {
    if (verbose) std::cerr << "montecl bench: " << s << "\n";
  };

  json r;
  r["scene"] = o.scene;
  r["device"] = device.name;
  r["platform"] = device.platformVersion;
  r["driver_version"] = device.driverVersion;
  r["compute_units"] = device.computeUnits;
  r["cpu_model"] = cpuModel();
  r["threads"] = threads;
  r["width"] = scene.camera.width;
  r["height"] = scene.camera.height;
  r["triangles"] = scene.triangles.size();
  r["repeat"] = o.repeat;
  r["rel_tolerance"] = o.relTolerance;

  // The tracers compared here (and Embree's) traverse one level: instances as placed copies,
  // refused like the loaders' copies when they would not fit in memory.
  if (!scene.instances.empty()) {
    const std::string tooMany = sceneMemoryRefusal(placedTriangleCount(scene), sizeof(SceneTriangle));
    if (!tooMany.empty()) throwInputError(scene.path, "instances", "bench traces flattened copies: the scene " + tooMany);
    flattenInstances(scene);
  }
  say("building the BVH over " + std::to_string(scene.triangles.size()) + " triangles");
  BvhBuildOptions buildOptions;
  buildOptions.splitBudget = o.splitBudget;
  Bvh bvh = buildBvh(scene.triangles, buildOptions);
  // Cut-outs: every tracer below applies the same alpha test (bench_alpha.h).
  std::vector<std::string> textureWarnings;
  const std::unique_ptr<BenchAlpha> alpha = makeBenchAlpha(scene, bvh, textureWarnings);
  for (const std::string& w : textureWarnings) std::cerr << "montecl: warning: " << scene.path << ": " << w << "\n";
  if (alpha) {
    r["alpha_tested_triangles"] = alpha->testedCount;
    r["texture_bytes"] = alpha->textures.bytes();
  }
  auto collapseStart = std::chrono::steady_clock::now();
  std::size_t nodeBytes = bvhNodeBytes(bvh, layout);  // the wide layout collapses the binary tree here
  const double collapseMs =
      layout == BvhLayout::Binary
          ? 0.0
          : std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - collapseStart).count();
  const double buildMs = bvh.buildMs + collapseMs;
  std::size_t bvhBytes = nodeBytes + bvh.triangles.size() * sizeof(Triangle);
  r["bvh"] = {{"layout", bvhLayoutName(layout)},
              {"build_ms", buildMs},
              {"binary_build_ms", bvh.buildMs},
              {"collapse_ms", collapseMs},
              {"nodes", bvh.nodes.size()},
              {"split_budget", o.splitBudget},
              {"references", bvh.triangles.size()},
              {"depth", bvh.depth},
              {"sah_cost", bvh.sahCost},
              {"bytes", bvhBytes},
              {"bytes_per_triangle", double(bvhBytes) / double(scene.triangles.size())},
              {"node_bytes_per_triangle", double(nodeBytes) / double(scene.triangles.size())}};
  r["rss_after_build_mb"] = peakRssMb();
  if (o.sahReference) {
    say("full-sweep SAH reference build");
    double sweep = fullSweepSahCost(scene.triangles, BvhBuildOptions{});
    r["bvh"]["sweep_sah_cost"] = sweep;
    r["bvh"]["sah_ratio"] = bvh.sahCost / sweep;
  }

  say("generating rays and host references on " + std::to_string(threads) + " threads");
  RaySets sets = makeRaySets(scene, bvh, threads, layout, alpha ? &alpha->host : nullptr);
  r["emitters"] = sets.emitters;

  std::unique_ptr<EmbreeTracer> embree;
  if (o.embree && !EmbreeTracer::available())
    std::cerr << "montecl: warning: built without Embree (install libembree-dev and reconfigure); no comparison\n";
  if (o.embree && EmbreeTracer::available()) {
    say("building the Embree scene");
    EmbreeTracer::AlphaTest test;
    if (alpha)
      test = [a = alpha.get()](std::uint32_t tri, float u, float v, const float3& org, const float3& dir) {
        return a->exists(tri, u, v, org, dir);
      };
    embree = std::make_unique<EmbreeTracer>(scene.triangles, threads, test,
                                            alpha ? alpha->tested : std::vector<std::uint8_t>{});
    r["embree_version"] = EmbreeTracer::version();
    r["embree"] = {{"build_ms", embree->buildMs()}};
    r["build_ratio"] = embree->buildMs() > 0.0 ? buildMs / embree->buildMs() : 0.0;
  }

  StageProgram program(device, layout, o.workGroupSize, /*profiling=*/true);
  ClSession& session = program.session();
  RayTracer tracer(program, bvh, alpha ? &scene : nullptr, alpha ? &alpha->textures : nullptr);
  r["local_size"] = session.localSize(session.kernel("intersect"));
  std::size_t total = 0;
  json rays = json::array();
  for (RaySet* set : {&sets.primary, &sets.ao, &sets.shadow, &sets.bounce}) {
    if (set->kind == "shadow" && sets.emitters == 0) continue;  // no emitters: no shadow rays
    say("tracing " + std::to_string(set->rays.size()) + " " + set->kind + " rays");
    std::vector<float> t;
    std::vector<std::uint8_t> occ;
    Timing dev = timeOnDevice(tracer, *set, o.warmup, o.repeat, t, occ);
    std::size_t mism = countMismatches(*set, t, occ, o.relTolerance);
    total += mism;
    std::size_t hits = 0;
    if (set->query == RayKind::Closest)
      for (float x : set->refT) hits += std::isfinite(x);
    else
      for (auto x : set->refOccluded) hits += x;
    json k = {{"kind", set->kind},
              {"query", set->query == RayKind::Closest ? "closest" : "any"},
              {"kernel", set->query == RayKind::Closest ? "intersect" : "intersect_shadow"},
              {"count", set->rays.size()},
              {"hits", hits},
              {"median_ms", dev.medianMs},
              {"min_ms", dev.minMs},
              {"mrays_per_s", mrays(set->rays.size(), dev.medianMs)},
              {"best_mrays_per_s", mrays(set->rays.size(), dev.minMs)},
              {"mismatches", mism},
              {"host_ref_mrays_per_s", mrays(set->rays.size(), set->refMs)}};
    if (layout == BvhLayout::Wide) {  // deterministic traversal work (bvh_visit_counts.h)
      VisitCounts vc = countWideVisits(bvh, set->rays, set->query == RayKind::Any,
                                       alpha ? &alpha->host : nullptr, threads);
      k["visits_nodes"] = vc.nodes;
      k["visits_leaves"] = vc.leaves;
    }
    if (embree) {
      std::vector<double> ms;
      std::vector<float> et;
      std::vector<std::uint8_t> eo;
      for (int rep = 0; rep < o.warmup + o.repeat; ++rep) {
        double m = set->query == RayKind::Closest ? embree->closest(set->rays, et) : embree->occluded(set->rays, eo);
        if (rep >= o.warmup) ms.push_back(m);
      }
      Timing e = summarize(ms);
      double emr = mrays(set->rays.size(), e.medianMs);
      k["embree_median_ms"] = e.medianMs;
      k["embree_min_ms"] = e.minMs;
      k["embree_mrays_per_s"] = emr;
      k["ratio"] = emr > 0.0 ? k["mrays_per_s"].get<double>() / emr : 0.0;
      // Informative only: Embree's watertight test may disagree with Moller-Trumbore on edges.
      k["embree_mismatches"] = countMismatches(*set, et, eo, o.relTolerance);
    }
    rays.push_back(k);
  }
  r["rays"] = rays;
  r["mismatches_total"] = total;
  r["peak_rss_mb"] = peakRssMb();
  return r;
}

std::string formatBenchTable(const json& r) {
  std::ostringstream s;
  s << std::fixed;
  const json& b = r["bvh"];
  s << "scene     " << r["scene"].get<std::string>() << ": " << r["triangles"].get<std::size_t>() << " triangles, "
    << r["emitters"].get<std::size_t>() << " emissive, " << r["width"].get<int>() << "x" << r["height"].get<int>()
    << "\n";
  s << "device    " << r["device"].get<std::string>() << " (" << r["platform"].get<std::string>() << "), "
    << r["compute_units"].get<unsigned>() << " compute units, local size " << r["local_size"].get<std::size_t>()
    << "\n";
  s << "cpu       " << r["cpu_model"].get<std::string>() << "; Embree and reference on "
    << r["threads"].get<unsigned>() << " threads\n";
  s << std::setprecision(1) << "bvh       " << b.value("layout", "wide") << " layout, build "
    << b["build_ms"].get<double>() << " ms, "
    << b["nodes"].get<std::size_t>() << " nodes, depth " << b["depth"].get<int>() << ", "
    << b.value("references", r["triangles"].get<std::size_t>()) << " triangle references (split budget "
    << std::setprecision(2) << b.value("split_budget", 0.0) << std::setprecision(1) << "), "
    << b["bytes_per_triangle"].get<double>() << " B/triangle (nodes "
    << b["node_bytes_per_triangle"].get<double>() << "), SAH cost " << std::setprecision(2)
    << b["sah_cost"].get<double>();
  if (b.contains("sweep_sah_cost"))
    s << " (full sweep " << b["sweep_sah_cost"].get<double>() << ", ratio " << std::setprecision(3)
      << b["sah_ratio"].get<double>() << ")";
  s << "\n";
  bool haveEmbree = r.contains("embree");
  if (haveEmbree)
    s << std::setprecision(1) << "embree    " << r["embree_version"].get<std::string>() << " build "
      << r["embree"]["build_ms"].get<double>() << " ms (RTC_BUILD_QUALITY_HIGH); build time ratio montecl/Embree "
      << std::setprecision(2) << r["build_ratio"].get<double>() << "\n";
  s << "\n";
  s << std::left << std::setw(9) << "rays" << std::right << std::setw(10) << "count" << std::setw(10) << "hits"
    << std::setw(11) << "median ms" << std::setw(10) << "min ms" << std::setw(10) << "Mrays/s" << std::setw(10) << "host ref";
  if (haveEmbree) s << std::setw(10) << "Embree" << std::setw(8) << "ratio";
  s << std::setw(12) << "mismatches";
  if (haveEmbree) s << std::setw(14) << "(Embree diff)";
  s << "\n";
  for (const json& k : r["rays"]) {
    s << std::left << std::setw(9) << k["kind"].get<std::string>() << std::right << std::setw(10)
      << k["count"].get<std::size_t>() << std::setw(10) << k["hits"].get<std::size_t>() << std::setprecision(2)
      << std::setw(11) << k["median_ms"].get<double>() << std::setw(10) << k["min_ms"].get<double>()
      << std::setw(10) << k["mrays_per_s"].get<double>() << std::setw(10) << k["host_ref_mrays_per_s"].get<double>();
    if (haveEmbree)
      s << std::setw(10) << k["embree_mrays_per_s"].get<double>() << std::setw(8) << k["ratio"].get<double>();
    s << std::setw(12) << k["mismatches"].get<std::size_t>();
    if (haveEmbree) s << std::setw(14) << k["embree_mismatches"].get<std::size_t>();
    s << "\n";
  }
  if (!r["rays"].empty() && r["rays"][0].contains("visits_nodes")) {
    s << "visits   " << std::setprecision(2);
    for (const json& k : r["rays"])
      s << " " << k["kind"].get<std::string>() << " " << k["visits_nodes"].get<double>() << " + "
        << k["visits_leaves"].get<double>();
    s << "  (per ray: wide nodes + leaves, counted on the host)\n";
  }
  s << "\nMrays/s from the median of " << r["repeat"].get<int>()
    << " runs (closest hit: intersect kernel, primary and diffuse bounce; any hit: intersect_shadow); ratio = montecl/Embree Mrays/s;\n"
    << "host ref: the same traversal code compiled for the host, one run on the same threads, no warm-up.\n"
    << "mismatch: hit/miss differs from the host reference, or t differs by more than "
    << std::setprecision(0) << std::scientific << r["rel_tolerance"].get<double>() << " relative. "
    << (r["mismatches_total"].get<std::size_t>() == 0 ? "All rays match." : "MISMATCHES FOUND.") << "\n";
  return s.str();
}

}  // namespace montecl
