// job.cpp: job/job.h.
#include "job/job.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "cl/devices.h"
#include "job/mpi.h"
#include "render/sample_schedule.h"
#include "util/errors.h"

namespace montecl::jobs {
namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Bytes of one pixel's exact state in a gather: mean, meanLo, m2, m2Lo, count (+ 2 AOV sums).
std::size_t pixelBytes(bool aovs) { return 4 * 16 + 8 + (aovs ? 16 * MCL_AOV_VECTORS : 0); }

std::vector<std::uint32_t> pixelsOfRank(int rank, int ranks, std::uint64_t pixels) {
  std::vector<std::uint32_t> out;
  for (std::uint64_t p = std::uint64_t(rank); p < pixels; p += std::uint64_t(ranks)) out.push_back(std::uint32_t(p));
  // More ranks than pixels: a spare rank renders pixel rank % pixels again (the same bits).
  if (out.empty()) out.push_back(std::uint32_t(std::uint64_t(rank) % pixels));
  return out;
}

}  // namespace

void addJobOptions(CLI::App* cmd, JobArgs& a) {
  cmd->add_option("--checkpoint", a.checkpoint,
                  "Write the exact film state to this file every --checkpoint-every seconds (atomically, at a "
                  "wave boundary), for --resume");
  cmd->add_option("--checkpoint-every", a.checkpointEvery, "Seconds between checkpoints (default 300)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--resume", a.resume,
                  "Continue the render saved in this checkpoint (same scene and settings): the image is "
                  "bit-identical to an uninterrupted render");
}

std::string deviceSpec(const std::string& spec) {
  const World& w = world();
  if (!w.active || !(spec.empty() || spec == "gpu" || spec == "GPU")) return spec;
  std::vector<DeviceInfo> gpus;
  for (const DeviceInfo& d : listDevices().devices)
    if (d.isGpu) gpus.push_back(d);
  if (gpus.empty()) return spec == "gpu" || spec == "GPU" ? "gpu" : spec;
  return deviceIndexString(gpus[std::size_t(w.localRank) % gpus.size()]);
}

Job::Job(const JobArgs& args, const Scene& scene, const RenderOptions& options) : args_(args) {
  const World& w = world();
  // A budget's rounds share their samples out over the whole image (render/adaptive_budget.h): a
  // rank sees its own pixels only, so its allocation would differ from one process's.
  if (w.active && w.size > 1 && scene.render.adaptive)
    throwInputError("--adaptive", "", "not with more than one MPI rank (each round shares samples out over the "
                                      "whole image, which no rank holds): render in one process, or use --target-error");
  width_ = scene.camera.width;
  height_ = scene.camera.height;
  aovs_ = options.aovs;
  targetError_ = options.targetError;
  errorFloor_ = options.errorFloor;
  // The render's identity hashes texture and environment files: only computed when a checkpoint
  // is written or read.
  if (!args_.checkpoint.empty() || !args_.resume.empty()) info_ = checkpointInfo(scene, options);
  if (!args_.resume.empty()) {
    resumed_ = readCheckpoint(args_.resume, info_, width_, height_);
    part_.initialFilm = &resumed_;
  }
  const std::uint64_t pixels = std::uint64_t(width_) * height_;
  if (w.active) {
    pixels_ = pixelsOfRank(w.rank, w.size, pixels);
    std::vector<std::uint32_t> render = pixels_;
    // MONTECL_DEBUG_DROP_PIXEL=N: the last rank skips pixel N (a wrong split the tests must catch).
    if (const char* drop = std::getenv("MONTECL_DEBUG_DROP_PIXEL"); drop && w.rank == w.size - 1)
      render.erase(std::remove(render.begin(), render.end(), std::uint32_t(std::atoll(drop))), render.end());
    if (render.empty()) render.push_back(pixels_.front());
    part_.pixels = render;
  }
  if (w.active || !args_.checkpoint.empty())
    part_.afterWave = [this](const std::function<Film()>& readFilm) { afterWave(readFilm); };
}

bool Job::writesImage() const { return world().rank == 0; }

void Job::afterWave(const std::function<Film()>& readFilm) {
  if (world().active) return exchange(false, readFilm);
  if (now() - lastCheckpoint_ >= args_.checkpointEvery) {
    saveCheckpoint(readFilm());
    lastCheckpoint_ = now();
  }
}

// A checkpoint that cannot be written (disk full, folder removed) is a warning: the render goes on
// and its image is still written. Warned at the first failure, again only after one succeeded.
void Job::saveCheckpoint(const Film& film) {
  try {
    writeCheckpoint(args_.checkpoint, info_, film);
    checkpointFailing_ = false;
  } catch (const std::exception& e) {
    if (checkpointFailing_) return;
    checkpointFailing_ = true;
    std::cerr << "montecl: warning: " << args_.checkpoint << ": checkpoint not written (" << e.what()
              << "); the render goes on\n";
  }
}

// One collective per wave (and per wait once this rank is done): sums of progress and stats, how
// many ranks are finished, and rank 0's checkpoint decision; then the checkpoint's gather if asked.
void Job::exchange(bool finished, const std::function<Film()>& readFilm) {
  const World& w = world();
  const bool wantCheckpoint =
      w.rank == 0 && !args_.checkpoint.empty() && now() - lastCheckpoint_ >= args_.checkpointEvery;
  std::vector<std::uint64_t> v{local_.samples,   std::max(localExpected_, local_.samples), local_.cameraRays,
                               local_.shadowRays, local_.waves, finished ? 1u : 0u, wantCheckpoint ? 1u : 0u,
                               local_.stoppedEarly ? 1u : 0u};
  allreduceSum(v);
  global_.samples = v[0];
  global_.cameraRays = v[2];
  global_.shadowRays = v[3];
  global_.waves = v[4];
  global_.stoppedEarly = v[7] > 0;
  global_.seconds = now() - started_;
  if (w.rank == 0 && progress_) progress_(v[0], v[1], global_);
  if (v[6]) {
    Film full = gather(readFilm());
    if (w.rank == 0) saveCheckpoint(full);
    lastCheckpoint_ = now();
  }
  allFinished_ = v[5] == std::uint64_t(w.size);
}

Film Job::gather(const Film& mine) const {
  const World& w = world();
  const std::size_t splits = mine.splits();  // the same on every rank (one scene and settings)
  const std::size_t bytes = pixelBytes(aovs_) + splits * 16;
  std::string send(pixels_.size() * bytes, '\0');
  char* at = send.data();
  for (std::uint32_t p : pixels_) {
    for (const auto* v : {&mine.mean, &mine.meanLo, &mine.m2, &mine.m2Lo}) std::memcpy(at, &(*v)[p], 16), at += 16;
    std::memcpy(at, &mine.count[p], 8), at += 8;
    if (aovs_) std::memcpy(at, &mine.aovSum[MCL_AOV_VECTORS * p], 16 * MCL_AOV_VECTORS), at += 16 * MCL_AOV_VECTORS;
    if (splits) std::memcpy(at, &mine.split[splits * p], 16 * splits), at += 16 * splits;
  }
  const std::uint64_t pixels = std::uint64_t(width_) * height_;
  std::vector<int> sizes, offsets;
  std::vector<std::vector<std::uint32_t>> lists;
  std::uint64_t total = 0;
  if (w.rank == 0)
    for (int r = 0; r < w.size; ++r) {
      lists.push_back(pixelsOfRank(r, w.size, pixels));
      offsets.push_back(int(total));
      sizes.push_back(int(lists.back().size() * bytes));
      total += lists.back().size() * bytes;
      if (total > 0x7fffffffull) throw RuntimeError("the film gather exceeds 2 GiB: use a smaller image");
    }
  std::string recv(total, '\0');
  gatherBytes(send, recv, sizes, offsets);
  if (w.rank != 0) return Film{};
  Film full;
  full.width = width_;
  full.height = height_;
  full.mean.assign(pixels, glm::vec4(0.0f));
  full.meanLo = full.m2 = full.m2Lo = full.mean;
  full.count.assign(pixels, 0);
  if (aovs_) full.aovSum.assign(MCL_AOV_VECTORS * pixels, glm::vec4(0.0f));
  full.split.assign(splits * pixels, glm::vec4(0.0f));
  const char* from = recv.data();
  for (int r = 0; r < w.size; ++r) {
    for (std::uint32_t p : lists[std::size_t(r)]) {
      for (auto* v : {&full.mean, &full.meanLo, &full.m2, &full.m2Lo}) std::memcpy(&(*v)[p], from, 16), from += 16;
      std::memcpy(&full.count[p], from, 8), from += 8;
      if (aovs_) std::memcpy(&full.aovSum[MCL_AOV_VECTORS * p], from, 16 * MCL_AOV_VECTORS), from += 16 * MCL_AOV_VECTORS;
      if (splits) std::memcpy(&full.split[splits * p], from, 16 * splits), from += 16 * splits;
    }
  }
  return full;
}

Film Job::render(WavefrontRenderer& renderer, const Scene& scene, const Bvh& bvh, RenderStats& stats,
                 const ProgressFn& progress, RenderPart part) {
  const World& w = world();
  started_ = lastCheckpoint_ = now();
  part.pixels = part_.pixels;
  part.initialFilm = part_.initialFilm;
  part.afterWave = part_.afterWave;
  if (!w.active) return renderer.render(scene, bvh, stats, progress, part);
  progress_ = progress;
  Film mine = renderer.render(scene, bvh, local_, [this](std::uint64_t, std::uint64_t total, const RenderStats& s) {
    local_ = s;
    localExpected_ = total;
  }, part);
  localExpected_ = local_.samples;
  const double busy = now() - started_;  // this rank's own work (render), before waiting for the others
  while (!allFinished_) exchange(true, [&] { return mine; });
  std::vector<std::uint64_t> busyUs(std::size_t(w.size), 0);
  busyUs[std::size_t(w.rank)] = std::uint64_t(busy * 1e6);
  allreduceSum(busyUs);
  if (w.rank == 0) {
    double sum = 0.0, most = 0.0;
    for (std::uint64_t us : busyUs) sum += double(us) * 1e-6, most = std::max(most, double(us) * 1e-6);
    std::cout << "mpi: " << w.size << " ranks, busy " << sum / w.size << " s mean, " << most
              << " s slowest: imbalance (slowest / mean) " << (sum > 0.0 ? most * w.size / sum : 1.0) << "\n";
  }
  Film full = gather(mine);
  full.correlated = mine.correlated;
  stats = local_;
  stats.samples = global_.samples;
  stats.cameraRays = global_.cameraRays;
  stats.shadowRays = global_.shadowRays;
  stats.waves = global_.waves;
  stats.stoppedEarly = global_.stoppedEarly;
  stats.seconds = now() - started_;
  stats.converged = 0;
  if (w.rank == 0 && targetError_ > 0.0)
    for (std::size_t p = 0; p < full.pixelCount(); ++p)
      stats.converged += relativeStandardError(full, p, errorFloor_) <= targetError_;
  return full;
}

}  // namespace montecl::jobs
