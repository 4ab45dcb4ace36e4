// stage_runner.h: the backend interface of the wave loop. One loop (wavefront.cpp) drives every
// backend through these calls, stage by stage; a backend owns the per-render buffers and runs the
// stage bodies (kernels/stages/*.h, named by the stage table) either as OpenCL kernels
// (cl_backend.cpp) or as plain C++ loops on the CPU (host_backend.cpp, `--device host`). Both bind
// a stage's arguments by name from StageBindings (render/stage_bindings.h).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "bvh/bvh.h"
#include "cl/devices.h"
#include "image/film.h"
#include "render/stage_bindings.h"
#include "render/stage_profile.h"
#include "texture/scene_textures.h"

namespace montecl {

// Everything a render uploads once, before the first wave.
struct StageInputs {
  FrameParams frame{};
  const Bvh* bvh = nullptr;
  std::vector<Material> materials;
  std::vector<Emitter> emitters;
  // Per-triangle attributes in BVH order (render/triangle_shading.h); empty: a 1-entry dummy.
  std::vector<TriangleShading> shading;
  // Vertex colours, 3 per triangle in BVH order (render/triangle_shading.h); empty: a 1-entry dummy.
  std::vector<float4> vertexColors;
  // Corner tangents, 3 per triangle in BVH order (render/triangle_shading.h); empty: a 1-entry dummy.
  std::vector<float4> tangents;
  // The scene's texture tables (FrameParams::textureCount entries); null or empty: no textures.
  const SceneTextures* textures = nullptr;
  // Triangles to upload instead of bvh->triangles (cut-outs flagged, alphaFlaggedTriangles); empty: those.
  std::vector<Triangle> triangles;
  std::vector<float4> envMap{float4(0.0f)};  // environment texels and CDFs (never empty)
  std::vector<float> envCdf{0.0f};
  std::vector<LightRecord> lightRecords{LightRecord{}};  // render/light_table.h (never empty)
  // The wave's size (items) and which buffers it needs (render/wave_buffers.h); its slots,
  // pixels and sub-sequence accumulators are taken from frame (setupShape).
  WaveShape shape;
  // The film state the render starts from (a resumed checkpoint); null: a cleared film.
  const Film* initialFilm = nullptr;
};

// The shape a backend allocates for: in.shape with at least one item, frame's slots, pixels and
// sub-sequence accumulators (the stages index those by the frame's values, so they must agree).
inline WaveShape setupShape(const StageInputs& in) {
  WaveShape s = in.shape;
  s.items = s.items ? s.items : 1;
  s.slots = in.frame.shadowSlots;
  s.pixels = std::uint64_t(in.frame.width) * in.frame.height;
  s.splits = in.frame.sobolSplits > 1 ? in.frame.sobolSplits : 0;
  return s;
}

// What a path bounce counted on the device (StageRunner::readBounceCounts).
struct BounceCounts {
  std::uint32_t paths = 0;       // live paths queued for the next bounce
  std::uint32_t shadowRays = 0;  // occlusion queries of this bounce
};

// What a wave counted on the device.
struct WaveCounts {
  std::uint32_t shadowRays = 0;  // occlusion queries traced
  std::uint32_t nanRays = 0;     // rays with a NaN/inf origin or direction (treated as misses)
};

class StageRunner {
 public:
  virtual ~StageRunner() = default;

  // Largest single buffer the backend can allocate (wave sizing and the clear "does not fit" error).
  virtual std::uint64_t maxAllocBytes() const = 0;
  // The BVH layout the stages traverse, resolved (Wide or Binary).
  virtual BvhLayout bvhLayout() const = 0;
  virtual bool programFromCache() const { return false; }
  virtual double programBuildMs() const { return 0.0; }

  // Allocates the wave buffers and uploads frame, BVH, attributes, materials and emitters; clears the film
  // (or loads in.initialFilm).
  virtual void setup(const StageInputs& in) = 0;
  // The packet stages' width W (1: scalar stage bodies only).
  virtual unsigned lanes() const { return 1; }
  // Replaces the active-pixel list the waves walk (setup starts with every pixel, in order) and
  // sets FrameParams::activeCount to its size and sampleBlockShift (the item order,
  // kernels/stages/stage_common.h) to blockShift.
  virtual void setActivePixels(const std::vector<std::uint32_t>& pixels, unsigned blockShift = 0) = 0;
  // Starts a wave of `count` items from global sample index waveStart: sets the bindings'
  // waveStart and waveCount, resets the ray count to `count` and the shadow queue count to 0.
  virtual void beginWave(std::uint64_t waveStart, std::uint32_t count) = 0;
  // Runs stage s over `items` work items (its body bounds them by its own count), reading the
  // camera or the bounce rays (RayInput). Stages run in launch order.
  virtual void launch(Stage s, std::uint64_t items, RayInput rays = RayInput::Camera) = 0;
  // Path tracing (render/path_waves.cpp). startBounce: sets the bounce index the stages get and
  // resets the shadow queue and the next-bounce queue counts to 0. endBounce: the next-bounce
  // queue (nextRays, nextPathIds, nextCount) becomes the current one (rays, pathIds, rayCount).
  // readBounceCounts: waits, returns the current queue's size and the last bounce's shadow count.
  virtual void startBounce(std::uint32_t bounce) = 0;
  virtual void endBounce() = 0;
  virtual BounceCounts readBounceCounts() = 0;
  // The end of a wave in two halves, so that the next wave can be queued before the host waits for this
  // one (the device then does not idle while the host books a wave): submitWave queues the reads
  // of the wave's counts (at most two waves submitted and not yet waited for); waitWave waits for
  // the oldest submitted wave and returns its counts.
  virtual void submitWave() = 0;
  virtual WaveCounts waitWave() = 0;
  // Reads the accumulated statistics (film.mean, film.m2, film.aovSum; the caller sets the size).
  virtual void readFilm(Film& film) = 0;
  // The render's last read of the film (as readFilm), which also releases every buffer: the film
  // part by part as it is read, so the film is never held whole twice. setup() starts again.
  virtual void finish(Film& film) = 0;
  // A render that ends by an exception: waits for what is queued and releases every buffer, so
  // that nothing queued reads the arrays a buffer uses in place after they are gone. No throw.
  virtual void abandon() noexcept {}
  // From now on, adds each launch's execution time to *profile by stageProfileName() (null:
  // stop), at the latest by the wave's waitWave(). OpenCL: needs a runner made with profiling.
  void setProfile(StageProfile* profile) { profile_ = profile; }

 protected:
  StageProfile* profile_ = nullptr;
};

// OpenCL kernels on `device` (its kernels built through the program cache); profiling: a queue
// with CL_QUEUE_PROFILING_ENABLE (for setProfile).
// lanes: the packet stages' width W (0: the device's, cl/device_tuning.h resolveLanes).
std::unique_ptr<StageRunner> makeClStageRunner(const DeviceInfo& device, std::size_t workGroupSize,
                                               BvhLayout layout = BvhLayout::Auto, bool profiling = false,
                                               unsigned lanes = 0);
// The stage functions compiled as C++, run on the CPU's threads.
std::unique_ptr<StageRunner> makeHostStageRunner();
// The runner for a device: the host backend when device.isHost, else OpenCL.
std::unique_ptr<StageRunner> makeStageRunner(const DeviceInfo& device, std::size_t workGroupSize,
                                             BvhLayout layout = BvhLayout::Auto, bool profiling = false,
                                             unsigned lanes = 0);

}  // namespace montecl
