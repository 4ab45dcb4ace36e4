// checkpoint.h: a render's exact film state on disk, so a killed render resumes bit-identically.
// Format (version 1, little-endian, docs/mpi.md): an 88-byte header, then the raw film arrays
//   char magic[8] = "MCLCKPT1"; u32 version = 1; u32 headerBytes = 88;
//   u64 key (renderKey: sceneDigest, settings, camera, everything else that changes a pixel);
//   u32 width, height, aovs (0, or MCL_AOV_VECTORS: 3; 1 was the older 2-vector film), seed, spp, firstSample, integrator, minSpp, maxSpp,
//   splits (K: the sobol sampler's sub-sequences with film accumulators, 0 without; was a 0 pad);
//   f64 targetError; u64 samplesDone (sum of counts); u64 payloadHash (FNV-1a of the payload);
//   payload: mean[P], meanLo[P], m2[P], m2Lo[P] (float4 each), count[P] (u64), aovSum[3P] (with AOVs),
//   split[K P] (float4, Film::split, with K > 0), roundTarget[P] (u64, Film::roundTarget: only for
//   render.adaptive, which the key records).
// It is written through util/atomic_file.h (temporary + rename), so a kill -9 at any moment leaves
// the previous checkpoint or the new one; a torn or foreign file fails its size, magic or hash check.
#pragma once
#include <cstdint>
#include <string>

#include "image/film.h"
#include "render/wavefront.h"
#include "scene/scene.h"

namespace montecl {

// Hash of everything that decides a pixel's value: the provenance's scene digest (geometry,
// materials, texture and environment contents, camera) and settings string, the frame, first
// sample, adaptive settings and AOVs (not the device, wave size or work-group size).
std::uint64_t renderKey(const Scene& scene, const RenderOptions& options);

struct CheckpointInfo {
  std::uint64_t key = 0;
  std::uint32_t seed = 0, spp = 0, firstSample = 0;
  bool aovs = false;
  bool adaptive = false;  // render.adaptive: the payload ends with the round targets
};

CheckpointInfo checkpointInfo(const Scene& scene, const RenderOptions& options);

// Writes film and info to path atomically.
void writeCheckpoint(const std::string& path, const CheckpointInfo& info, const Film& film);

// Whether path is a file that starts like a montecl checkpoint (its magic): the only kind of
// existing file --checkpoint may replace.
bool isCheckpointFile(const std::string& path);

// Reads a checkpoint written for `expected` (same key, size and AOVs); anything else, or a
// damaged file, or a path that is not a regular file, is an InputError naming the file (exit 2).
Film readCheckpoint(const std::string& path, const CheckpointInfo& expected, int width, int height);

}  // namespace montecl
