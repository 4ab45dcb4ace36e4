// job.h: one render as a job: alone, or split among the ranks of an MPI job (job/mpi.h), with
// optional checkpoints and resume (render/checkpoint.h). Under MPI rank r of K renders the pixels
// p with p % K == r (interleaved: near-equal cost per rank), one Iallreduce per wave carries the
// job's progress (rank 0's bar shows the whole job) and the checkpoint decision (rank 0's clock),
// and rank 0 gathers every rank's exact film state (MPI_Igatherv) and writes the image. Each
// pixel's samples are accumulated in sample order on one rank, so the image is bit-identical to
// one process for any K.
#pragma once
#include <string>

#include "render/checkpoint.h"
#include "render/wavefront.h"

namespace CLI {
class App;
}

namespace montecl::jobs {

struct JobArgs {
  std::string checkpoint, resume;
  double checkpointEvery = 300.0;
};

// --checkpoint, --checkpoint-every, --resume.
void addJobOptions(CLI::App* cmd, JobArgs& args);

// The --device spec for this rank: under MPI, with spec empty or "gpu", the node-local rank picks
// a GPU: GPU (localRank % GPUs on the node), as "P:D" (no GPU: spec unchanged, the usual choice).
std::string deviceSpec(const std::string& spec);

class Job {
 public:
  // Joins MPI when launched by it; reads --resume (refusing another render's checkpoint); decides
  // this rank's pixels, the film it resumes and what runs after each wave.
  Job(const JobArgs& args, const Scene& scene, const RenderOptions& options);
  // Renders `part` (the caller's textures and prepared triangles) with the job's pixels, resumed
  // film and per-wave hook; on the rank that writes (rank 0, or alone) returns the whole film and
  // the job's stats.
  Film render(WavefrontRenderer& renderer, const Scene& scene, const Bvh& bvh, RenderStats& stats,
              const ProgressFn& progress, RenderPart part);
  bool writesImage() const;

 private:
  void afterWave(const std::function<Film()>& readFilm);
  void exchange(bool finished, const std::function<Film()>& readFilm);
  Film gather(const Film& mine) const;
  void saveCheckpoint(const Film& film);

  JobArgs args_;
  CheckpointInfo info_;
  Film resumed_;
  std::vector<std::uint32_t> pixels_;  // this rank's share (MPI)
  RenderPart part_;                    // what the job decided of each render call
  int width_ = 0, height_ = 0;
  bool aovs_ = false;
  double targetError_ = 0.0, errorFloor_ = 0.0;
  double started_ = 0.0, lastCheckpoint_ = 0.0;
  ProgressFn progress_;
  RenderStats local_, global_;
  std::uint64_t localExpected_ = 0;
  bool allFinished_ = false;
  bool checkpointFailing_ = false;  // the last checkpoint write failed (warned)
};

}  // namespace montecl::jobs
