// stage_table.h: every wavefront stage and its kernel arguments, declared once (X-macros, as
// Cycles declares its kernel state once). Reads and writes nothing. From this table come:
// - the stage's argument struct <stage>_args (below), the one parameter of its body
//   stage_<stage>(const <stage>_args* a, uint item) in kernels/stages/<stage>.h;
// - the OpenCL kernel signature and the struct it builds (kernels/montecl.cl);
// - the OpenCL argument binding and the host backend's call (host/render/stage_bindings.h), both
//   by name from StageBindings, so a table name that no binding has does not compile.
// Every stage also receives `frame` (the render's FrameParams) as its first argument.
// Adding a stage: write kernels/stages/<stage>.h, add STAGE(<stage>) to MCL_STAGES and
// its MCL_ARGS_<stage> list here, and launch it from the wave loop (host/render/wavefront.cpp).
#pragma once
#include "traverse.h"  // BvhTraversalNode: the node type of the layout the program is built for

#define MCL_STAGES(STAGE)                                                                          \
  STAGE(generate)                                                                                  \
  STAGE(intersect)                                                                                 \
  STAGE(shade_ao)                                                                                  \
  STAGE(shade_direct)                                                                              \
  STAGE(shade_direct_hit)                                                                          \
  STAGE(intersect_shadow)                                                                          \
  STAGE(accumulate)                                                                                \
  STAGE(record_aov)                                                                                \
  STAGE(accumulate_aov)                                                                            \
  STAGE(shade_path)                                                                                \
  STAGE(path_gather)                                                                               \
  STAGE(wave_ao)                                                                                   \
  STAGE(wave_direct)                                                                               \
  STAGE(wave_path)

// Every stage's body stage_<stage>(a, first) takes MCL_LANES (W, kernels/shared/lanes.h)
// consecutive items from `first`, one per lane (lanes past the stage's count masked): the OpenCL
// kernel passes first = get_global_id(0) W and the host launches ceil(items / W) work items; the host
// backend, at W = 1, calls it per item. The fused stages (kernels/stages/wave_fused.h) take group
// first / W of W C items.

// Each integrator's wave, written once: its stages from the intersection of the wave's rays to its
// occlusion queries, in launch order. STEP(stage, rays, queries): rays Camera (the wave's own rays
// and hits) or Bounce (direct lighting's BSDF rays); queries Push where the stage pushes occlusion
// queries, else None. Expanded into the host's launches (host/render/integrators.cpp,
// path_waves.cpp) and the fused stages' bodies (kernels/stages/wave_fused.h). Around it every wave
// runs generate first (a path: at bounce 0), then record_aov (AOVs on; a path: at bounce 0),
// intersect_shadow, and accumulate (a path: path_gather each bounce, accumulate at its end).
#define MCL_SCHEDULE_ao(STEP) STEP(intersect, Camera, None) STEP(shade_ao, Camera, Push)
#define MCL_SCHEDULE_direct(STEP)                                                                  \
  STEP(intersect, Camera, None) STEP(shade_direct, Camera, Push) STEP(intersect, Bounce, None)     \
  STEP(shade_direct_hit, Camera, None)
#define MCL_SCHEDULE_path(STEP) STEP(intersect, Camera, None) STEP(shade_path, Camera, Push)

// The texture tables (kernels/shared/texture.h): what albedo lookups read.
#define MCL_TEXTURE_ARGS(ARG)                                                                      \
  ARG(MCL_GLOBAL const TextureDesc*, textures) ARG(MCL_GLOBAL const TextureLevel*, textureLevels)  \
  ARG(MCL_GLOBAL const ushort*, texels) ARG(MCL_GLOBAL const float4*, vertexColors)
// What the stages that shade read beside: the corner tangents of glTF TANGENT (3 float4 per
// triangle, BVH order; a 1-entry dummy when no triangle has them), for normal maps only, so the
// traversal stages do not bind them.
#define MCL_SHADE_TEXTURE_ARGS(ARG) MCL_TEXTURE_ARGS(ARG) ARG(MCL_GLOBAL const float4*, tangents)
// What the alpha test of cut-outs reads (surface_texture.h AlphaScene).
#define MCL_ALPHA_ARGS(ARG)                                                                        \
  ARG(MCL_GLOBAL const Material*, materials) ARG(MCL_GLOBAL const TriangleShading*, shading)       \
  MCL_TEXTURE_ARGS(ARG)

// A two-level BVH's placements (Instance; a 1-entry dummy without instances) and, for the stages
// that shade hits, the instance of each hit (intersect writes it; read only when
// frame->instanceCount > 0, stage_common.h hit_instance).
#define MCL_INSTANCE_ARGS(ARG) ARG(MCL_GLOBAL const Instance*, instances)
#define MCL_HIT_INSTANCE_ARGS(ARG) MCL_INSTANCE_ARGS(ARG) ARG(MCL_GLOBAL const uint*, hitInstances)
// The shading stages' lane tally (--profile; FrameParams::countLanes): hits shaded in lane types
// and hits shaded one by one.
#define MCL_LANE_TALLY_ARGS(ARG) ARG(MCL_GLOBAL volatile uint*, packedLanes) ARG(MCL_GLOBAL volatile uint*, aloneLanes)

// ARG(type, name): the names are StageBindings' members (host/render/stage_bindings.h).
// normals: per BVH-ordered triangle, xyz its unit geometric normal and w its area, computed once
// on the host (host/render/triangle_shading.h buildTriangleNormals) with the kernels' own functions.
#define MCL_ARGS_generate(ARG)                                                                     \
  ARG(ulong, waveStart) ARG(uint, waveCount) ARG(MCL_GLOBAL const uint*, active)                   \
  ARG(MCL_GLOBAL Ray*, rays)

#define MCL_ARGS_intersect(ARG)                                                                    \
  ARG(MCL_GLOBAL const BvhTraversalNode*, nodes) ARG(MCL_GLOBAL const Triangle*, tris)             \
  ARG(MCL_GLOBAL const Ray*, rays) ARG(MCL_GLOBAL const uint*, rayCount) ARG(MCL_GLOBAL Hit*, hits) \
  ARG(MCL_GLOBAL volatile uint*, nanRays) \
  MCL_ALPHA_ARGS(ARG) MCL_INSTANCE_ARGS(ARG) ARG(MCL_GLOBAL uint*, hitInstances)

#define MCL_ARGS_shade_ao(ARG)                                                                     \
  ARG(ulong, waveStart) ARG(uint, waveCount) ARG(MCL_GLOBAL const uint*, active)                   \
  ARG(MCL_GLOBAL const Triangle*, tris) ARG(MCL_GLOBAL const TriangleShading*, shading) ARG(MCL_GLOBAL const float4*, normals) \
  ARG(MCL_GLOBAL const Ray*, rays)                                                                 \
  ARG(MCL_GLOBAL const Hit*, hits) ARG(MCL_GLOBAL float4*, radiance)                               \
  ARG(MCL_GLOBAL float4*, shadowContrib) ARG(MCL_GLOBAL ShadowWork*, queue)                        \
  ARG(MCL_GLOBAL volatile uint*, queueCount) MCL_HIT_INSTANCE_ARGS(ARG)

#define MCL_ARGS_shade_direct(ARG)                                                                 \
  ARG(ulong, waveStart) ARG(uint, waveCount) ARG(MCL_GLOBAL const uint*, active)                   \
  ARG(MCL_GLOBAL const Triangle*, tris) ARG(MCL_GLOBAL const TriangleShading*, shading) ARG(MCL_GLOBAL const float4*, normals) \
  ARG(MCL_GLOBAL const Material*, materials)                                                       \
  ARG(MCL_GLOBAL const Emitter*, emitters) ARG(MCL_GLOBAL const Ray*, rays)                        \
  ARG(MCL_GLOBAL const Hit*, hits) ARG(MCL_GLOBAL float4*, radiance)                               \
  ARG(MCL_GLOBAL float4*, shadowContrib) ARG(MCL_GLOBAL ShadowWork*, queue)                        \
  ARG(MCL_GLOBAL volatile uint*, queueCount) ARG(MCL_GLOBAL Ray*, bounce)                        \
  ARG(MCL_GLOBAL const float4*, envMap) ARG(MCL_GLOBAL const float*, envCdf) \
  ARG(MCL_GLOBAL const LightRecord*, lightRecords) \
  MCL_SHADE_TEXTURE_ARGS(ARG) MCL_HIT_INSTANCE_ARGS(ARG) MCL_LANE_TALLY_ARGS(ARG)

#define MCL_ARGS_shade_direct_hit(ARG)                                                             \
  ARG(ulong, waveStart) ARG(uint, waveCount) ARG(MCL_GLOBAL const uint*, active)                   \
  ARG(MCL_GLOBAL const Triangle*, tris)                                                            \
  ARG(MCL_GLOBAL const TriangleShading*, shading) ARG(MCL_GLOBAL const float4*, normals) \
  ARG(MCL_GLOBAL const Material*, materials) ARG(MCL_GLOBAL const Ray*, rays)                      \
  ARG(MCL_GLOBAL const Hit*, hits) ARG(MCL_GLOBAL const Ray*, bounce)                              \
  ARG(MCL_GLOBAL const Hit*, bounceHits) ARG(MCL_GLOBAL float4*, shadowContrib)                   \
  ARG(MCL_GLOBAL const float4*, envMap) \
  MCL_SHADE_TEXTURE_ARGS(ARG) MCL_HIT_INSTANCE_ARGS(ARG)

#define MCL_ARGS_intersect_shadow(ARG)                                                             \
  ARG(MCL_GLOBAL const BvhTraversalNode*, nodes) ARG(MCL_GLOBAL const Triangle*, tris)             \
  ARG(MCL_GLOBAL const ShadowWork*, queue) ARG(MCL_GLOBAL const uint*, queueCount)                 \
  ARG(MCL_GLOBAL float4*, shadowContrib) ARG(MCL_GLOBAL volatile uint*, nanRays) \
  MCL_ALPHA_ARGS(ARG) MCL_INSTANCE_ARGS(ARG)

#define MCL_ARGS_accumulate(ARG)                                                                   \
  ARG(ulong, waveStart) ARG(uint, waveCount) ARG(MCL_GLOBAL const uint*, active)                   \
  ARG(MCL_GLOBAL const float4*, radiance) ARG(MCL_GLOBAL const float4*, shadowContrib)             \
  ARG(MCL_GLOBAL float4*, mean) ARG(MCL_GLOBAL float4*, meanLo) ARG(MCL_GLOBAL float4*, m2)          \
  ARG(MCL_GLOBAL float4*, m2Lo) ARG(MCL_GLOBAL float4*, split)

#define MCL_ARGS_record_aov(ARG)                                                                   \
  ARG(ulong, waveStart) ARG(uint, waveCount) ARG(MCL_GLOBAL const uint*, active)                   \
  ARG(MCL_GLOBAL const Triangle*, tris)                                                            \
  ARG(MCL_GLOBAL const TriangleShading*, shading) ARG(MCL_GLOBAL const float4*, normals) \
  ARG(MCL_GLOBAL const Material*, materials) ARG(MCL_GLOBAL const Ray*, rays)                      \
  ARG(MCL_GLOBAL const Hit*, hits) ARG(MCL_GLOBAL const float4*, radiance) ARG(MCL_GLOBAL float4*, aov) \
  MCL_SHADE_TEXTURE_ARGS(ARG) MCL_HIT_INSTANCE_ARGS(ARG)

#define MCL_ARGS_accumulate_aov(ARG)                                                               \
  ARG(ulong, waveStart) ARG(uint, waveCount) ARG(MCL_GLOBAL const uint*, active)                   \
  ARG(MCL_GLOBAL const float4*, aov) ARG(MCL_GLOBAL float4*, aovSum)

// Path tracing (kernels/stages/shade_path.h): rays, hits and pathIds are the bounce's compacted
// queue of *rayCount live paths; per-path state is indexed by path id (the wave item).
#define MCL_ARGS_shade_path(ARG)                                                                   \
  ARG(ulong, waveStart) ARG(uint, pathBounce) ARG(MCL_GLOBAL const uint*, active)                  \
  ARG(MCL_GLOBAL const Triangle*, tris) ARG(MCL_GLOBAL const TriangleShading*, shading) ARG(MCL_GLOBAL const float4*, normals) \
  ARG(MCL_GLOBAL const Material*, materials)                                                       \
  ARG(MCL_GLOBAL const Emitter*, emitters) ARG(MCL_GLOBAL const Ray*, rays)                        \
  ARG(MCL_GLOBAL const Hit*, hits) ARG(MCL_GLOBAL const uint*, rayCount)                           \
  ARG(MCL_GLOBAL const uint*, pathIds) ARG(MCL_GLOBAL float4*, radiance)                           \
  ARG(MCL_GLOBAL float4*, throughput) ARG(MCL_GLOBAL float4*, shadowContrib)                       \
  ARG(MCL_GLOBAL ShadowWork*, queue) ARG(MCL_GLOBAL volatile uint*, queueCount)                    \
  ARG(MCL_GLOBAL Ray*, nextRays) ARG(MCL_GLOBAL uint*, nextPathIds)                                \
  ARG(MCL_GLOBAL volatile uint*, nextCount) ARG(MCL_GLOBAL const float4*, envMap)                   \
  ARG(MCL_GLOBAL const float*, envCdf) ARG(MCL_GLOBAL const LightRecord*, lightRecords) \
  MCL_SHADE_TEXTURE_ARGS(ARG) MCL_HIT_INSTANCE_ARGS(ARG) MCL_LANE_TALLY_ARGS(ARG)

#define MCL_ARGS_path_gather(ARG)                                                                  \
  ARG(uint, pathBounce) ARG(MCL_GLOBAL const uint*, rayCount) ARG(MCL_GLOBAL const uint*, pathIds) \
  ARG(MCL_GLOBAL float4*, shadowContrib) ARG(MCL_GLOBAL float4*, radiance)

// The fused stages (kernels/stages/wave_fused.h): every argument of the stages they run, once each
// (const only where no stage writes it), and groupCounts, a count per group of items.
#define MCL_ARGS_wave_ao(ARG)                                                                      \
  ARG(ulong, waveStart) ARG(uint, waveCount) ARG(MCL_GLOBAL const uint*, active)                   \
  ARG(MCL_GLOBAL const BvhTraversalNode*, nodes) ARG(MCL_GLOBAL const Triangle*, tris)             \
  ARG(MCL_GLOBAL Ray*, rays) ARG(MCL_GLOBAL const uint*, rayCount) ARG(MCL_GLOBAL Hit*, hits)      \
  ARG(MCL_GLOBAL volatile uint*, nanRays) MCL_ALPHA_ARGS(ARG)                                      \
  ARG(MCL_GLOBAL const float4*, normals) ARG(MCL_GLOBAL float4*, radiance)                         \
  ARG(MCL_GLOBAL float4*, shadowContrib) ARG(MCL_GLOBAL ShadowWork*, queue)                        \
  ARG(MCL_GLOBAL volatile uint*, queueCount) ARG(MCL_GLOBAL volatile uint*, groupCounts)           \
  ARG(MCL_GLOBAL float4*, mean) ARG(MCL_GLOBAL float4*, meanLo) ARG(MCL_GLOBAL float4*, m2)          \
  ARG(MCL_GLOBAL float4*, m2Lo) ARG(MCL_GLOBAL float4*, split)                                     \
  MCL_INSTANCE_ARGS(ARG) ARG(MCL_GLOBAL uint*, hitInstances)                                       \
  ARG(MCL_GLOBAL const float4*, tangents) ARG(MCL_GLOBAL float4*, aov) ARG(MCL_GLOBAL float4*, aovSum)

#define MCL_ARGS_wave_direct(ARG)                                                                  \
  MCL_ARGS_wave_ao(ARG) ARG(MCL_GLOBAL const Emitter*, emitters) ARG(MCL_GLOBAL Ray*, bounce)      \
  ARG(MCL_GLOBAL Hit*, bounceHits) ARG(MCL_GLOBAL const float4*, envMap)                           \
  ARG(MCL_GLOBAL const float*, envCdf) ARG(MCL_GLOBAL const LightRecord*, lightRecords)            \
  ARG(MCL_GLOBAL uint*, bounceHitInstances) MCL_LANE_TALLY_ARGS(ARG)

#define MCL_ARGS_wave_path(ARG)                                                                    \
  ARG(ulong, waveStart) ARG(uint, waveCount) ARG(uint, pathBounce) ARG(MCL_GLOBAL const uint*, active) \
  ARG(MCL_GLOBAL const BvhTraversalNode*, nodes) ARG(MCL_GLOBAL const Triangle*, tris)             \
  ARG(MCL_GLOBAL Ray*, rays) ARG(MCL_GLOBAL const uint*, rayCount) ARG(MCL_GLOBAL Hit*, hits)      \
  ARG(MCL_GLOBAL volatile uint*, nanRays) MCL_ALPHA_ARGS(ARG)                                      \
  ARG(MCL_GLOBAL const float4*, normals) ARG(MCL_GLOBAL const Emitter*, emitters)                  \
  ARG(MCL_GLOBAL uint*, pathIds) ARG(MCL_GLOBAL float4*, radiance)                                 \
  ARG(MCL_GLOBAL float4*, throughput) ARG(MCL_GLOBAL float4*, shadowContrib)                       \
  ARG(MCL_GLOBAL ShadowWork*, queue) ARG(MCL_GLOBAL volatile uint*, queueCount)                    \
  ARG(MCL_GLOBAL volatile uint*, groupCounts) ARG(MCL_GLOBAL Ray*, nextRays)                       \
  ARG(MCL_GLOBAL uint*, nextPathIds) ARG(MCL_GLOBAL volatile uint*, nextCount)                     \
  ARG(MCL_GLOBAL const float4*, envMap) ARG(MCL_GLOBAL const float*, envCdf)                       \
  ARG(MCL_GLOBAL const LightRecord*, lightRecords) MCL_INSTANCE_ARGS(ARG) ARG(MCL_GLOBAL uint*, hitInstances) \
  ARG(MCL_GLOBAL const float4*, tangents) ARG(MCL_GLOBAL float4*, aov) MCL_LANE_TALLY_ARGS(ARG)

// <stage>_args: frame, then the table's arguments, as fields of the same names.
#define MCL_ARG_FIELD(type, name) type name;
#define MCL_STAGE_ARGS_STRUCT(stage)                                                               \
  typedef struct {                                                                                 \
    MCL_CONSTANT const FrameParams* frame;                                                         \
    MCL_ARGS_##stage(MCL_ARG_FIELD)                                                                \
  } stage##_args;

MCL_STAGES(MCL_STAGE_ARGS_STRUCT)
