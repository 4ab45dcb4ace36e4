// integrators.h: one description per integrator, declared once: its stage schedule for a wave,
// the buffers and occlusion slots it needs, whether it reads the lights, and how its rays are
// counted. The wave loop (wavefront.cpp), the checkpoint key, the wave sizing and the memory
// check ask it instead of testing which integrator runs; the render settings each integrator reads
// are marked in the settings table (scene/render_settings.h). Adding an integrator: a value of
// Integrator and its name (scene/render_choices.*), its settings' marks, and one row here with its
// schedule. Reads and writes nothing.
#pragma once
#include <cstdint>

#include "render/path_waves.h"
#include "render/stage_runner.h"
#include "render/wave_buffers.h"
#include "scene/scene.h"
#include "texture/scene_textures.h"

namespace montecl {

struct IntegratorDesc {
  Integrator id;
  bool bounce;      // traces BRDF rays within the wave: the bounce buffers (direct lighting)
  bool path;        // keeps path state between bounces, which the host sizes from counts it reads
                    // back: the path buffers, no wave queued ahead, counts from PathWaveCounts
  bool lit;         // reads the emitters and the environment; otherwise only the background
  // Occlusion queries per pixel sample: the shadow slots of FrameParams and the wave buffers.
  std::uint32_t (*shadowSlots)(const RenderSettings&);
  // Rays traced per pixel sample besides the camera ray and the occlusion queries, known up front
  // (direct lighting's BRDF ray; path tracing counts its continuations in PathWaveCounts).
  std::uint32_t (*extraRays)(const RenderSettings&);
  // Launches one wave of n items after generate and before accumulate (AOVs recorded when aovs).
  // fused: path tracing's bounces each as one launch of its fused stage, which generates too.
  void (*launchWave)(StageRunner& run, std::uint32_t n, std::uint32_t slots, bool aovs, bool fused,
                     PathWaveCounts& counts);
  // The fused stage (kernels/stages/wave_fused.h), when `fusable`: AO and direct run a whole wave,
  // generate to accumulate, in one launch where it applies; path tracing one launch per bounce.
  bool fusable;
  Stage fused;
};

const IntegratorDesc& integratorDesc(Integrator integrator);

// The textures a render of this integrator reads (the cut-outs' alpha ones always): the lit
// integrators every kind; AO none of the others, unless the film records AOVs (aovs), whose albedo
// reads the reflectance textures and whose normal reads the normal maps.
TextureUses textureUsesOf(const IntegratorDesc& integrator, bool aovs);

// What a wave of `items` items of this render needs (render/wave_buffers.h).
WaveShape waveShapeFor(const Scene& scene, std::uint64_t items, bool aovs);

}  // namespace montecl
