// integrators.cpp: the integrator table (integrators.h) and each integrator's stage schedule.
#include "render/integrators.h"

#include <stdexcept>

#include "kernels/shared/rng.h"

namespace montecl {
namespace {

// Path tracing's random-number layout gives each bounce 1 + the most light samples groups.
static_assert(MCL_DIM_PATH_STRIDE == 1u + kMaxLightSamples, "rng.h's path stride must cover every light sample");

// An AO or direct wave after generate: the stage table's schedule (MCL_SCHEDULE_<integrator>),
// the first-hit AOVs, the occlusion queries (slots per item).
#define MCL_HOST_STEP(stage, rays, queries) run.launch(Stage::stage, n, RayInput::rays);
void waveTail(StageRunner& run, std::uint32_t n, std::uint32_t slots, bool aovs) {
  if (aovs) run.launch(Stage::record_aov, n);
  run.launch(Stage::intersect_shadow, std::uint64_t(n) * slots);
}
void aoWave(StageRunner& run, std::uint32_t n, std::uint32_t slots, bool aovs, bool, PathWaveCounts&) {
  MCL_SCHEDULE_ao(MCL_HOST_STEP)
  waveTail(run, n, slots, aovs);
}
// shade_direct queues the light samples and a BRDF ray, whose hit shade_direct_hit weighs.
void directWave(StageRunner& run, std::uint32_t n, std::uint32_t slots, bool aovs, bool, PathWaveCounts&) {
  MCL_SCHEDULE_direct(MCL_HOST_STEP)
  waveTail(run, n, slots, aovs);
}
#undef MCL_HOST_STEP

// The bounce loop (render/path_waves.cpp), on the live paths only.
void pathWave(StageRunner& run, std::uint32_t n, std::uint32_t slots, bool aovs, bool fused, PathWaveCounts& counts) {
  runPathWave(run, n, slots, aovs, fused, counts);
}

std::uint32_t one(const RenderSettings&) { return 1; }
std::uint32_t none(const RenderSettings&) { return 0; }
// A slot per light sample and one for the BRDF sample's emitter hit.
std::uint32_t directSlots(const RenderSettings& r) { return std::uint32_t(r.lightSamples) + 1; }
std::uint32_t pathSlots(const RenderSettings& r) { return std::uint32_t(r.lightSamples); }
std::uint32_t brdfRay(const RenderSettings& r) { return r.directSampling != DirectSampling::Light ? 1 : 0; }

//                                     id                  bounce path   lit    slots        extra rays  schedule    fused stage
const IntegratorDesc kIntegrators[] = {{Integrator::Ao,     false, false, false, one,         none,       aoWave,     true,  Stage::wave_ao},
                                       {Integrator::Direct, true,  false, true,  directSlots, brdfRay,    directWave, true,  Stage::wave_direct},
                                       {Integrator::Path,   false, true,  true,  pathSlots,   none,       pathWave,   true,  Stage::wave_path}};

}  // namespace

const IntegratorDesc& integratorDesc(Integrator integrator) {
  for (const IntegratorDesc& d : kIntegrators)
    if (d.id == integrator) return d;
  throw std::logic_error("integratorDesc: an integrator without a row");
}

TextureUses textureUsesOf(const IntegratorDesc& integrator, bool aovs) {
  TextureUses u;
  u.reflectance = integrator.lit || aovs;
  u.emission = integrator.lit;
  u.normal = integrator.lit || aovs;
  return u;
}

WaveShape waveShapeFor(const Scene& scene, std::uint64_t items, bool aovs) {
  const IntegratorDesc& d = integratorDesc(scene.render.integrator);
  WaveShape s;
  s.items = items;
  s.slots = d.shadowSlots(scene.render);
  s.pixels = std::uint64_t(scene.camera.width) * std::uint64_t(scene.camera.height);
  s.bounce = d.bounce;
  s.path = d.path;
  s.aovs = aovs;
  if (sobolSplitsUsed(scene.render) > 1) s.splits = std::uint64_t(sobolSplitsUsed(scene.render));
  return s;
}

}  // namespace montecl
