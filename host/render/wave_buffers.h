// wave_buffers.h: every buffer the wave loop allocates per render, declared once: its name (the
// StageBindings member the stage table's arguments refer to), element type, how many elements
// (per wave item, per occlusion slot, per pixel) and which renders need it. StageBindings declares
// its members from these lists, both backends allocate, bind and release them by iterating them,
// and the wave sizing and the memory check add their bytes from them (waveBytesPerItem,
// filmBytesPerPixel), so a new buffer is one row here plus the stages that use it. The read-only
// scene tables are listed here too (MCL_SCENE_TABLES). Reads and writes nothing.
#pragma once
#include <cstdint>

#include "kernels/shared/types.h"

namespace montecl {

// How many elements a buffer holds, for a wave of `items` items with `slots` occlusion queries
// each, on an image of `pixels` pixels.
enum class Per { Item, Slot, AovsPerItem, Pixel, AovsPerPixel, SplitsPerPixel, One };  // Aovs: MCL_AOV_VECTORS
// Which renders need it; the others get a 1-element dummy (OpenCL has no empty buffers).
enum class Need { Always, Bounce, Path, Aovs, Splits, Instances, BounceInstances };

// WAVE_BUFFER(name, element type, Per, Need): written and read by the stages only.
// bounce / bounceHits: direct lighting's BRDF rays and their hits; throughput, nextRays, pathIds,
// nextPathIds: path tracing's per-path state and the next bounce's compacted queue (swapped with
// rays / pathIds between bounces); aov: first-hit albedo+depth, normal, emission of each item;
// groupCounts: the fused stages' occlusion queries per group of items (kernels/stages/wave_fused.h;
// a group is at least one item, so one entry per item is enough); hitInstances / bounceHitInstances:
// the instance of each hit in hits / bounceHits (an index into the scene's Instance array, or
// MCL_NO_INSTANCE for world-space triangles), with a two-level BVH only.
#define MCL_WAVE_BUFFERS(B)             \
  B(rays, Ray, Item, Always)            \
  B(hits, Hit, Item, Always)            \
  B(bounce, Ray, Item, Bounce)          \
  B(bounceHits, Hit, Item, Bounce)      \
  B(radiance, float4, Item, Always)     \
  B(shadowContrib, float4, Slot, Always) \
  B(queue, ShadowWork, Slot, Always)    \
  B(throughput, float4, Item, Path)     \
  B(nextRays, Ray, Item, Path)          \
  B(pathIds, uint, Item, Path)          \
  B(nextPathIds, uint, Item, Path)      \
  B(aov, float4, AovsPerItem, Aovs)     \
  B(groupCounts, uint, Item, Always)    \
  B(hitInstances, uint, Item, Instances) \
  B(bounceHitInstances, uint, Item, BounceInstances)

// WAVE_COUNTER(name): one uint the stages count into (atomically) and the host resets and reads:
// rayCount the current ray queue's size, nextCount the next bounce's, queueCount the occlusion
// queries queued, nanRays rays met with a NaN/inf origin or direction; with --profile
// (FrameParams::countLanes) the shading stages' hits shaded in lane types (packedLanes) and one by
// one through the scalar functions (aloneLanes: other kinds, normal and bump maps, instances).
#define MCL_WAVE_COUNTERS(C) C(rayCount) C(nextCount) C(queueCount) C(nanRays) C(packedLanes) C(aloneLanes)

// FILM_BUFFER(name, Per, Need): the film, per pixel, float4 (kernels/stages/accumulate.h:
// float-float mean and M2 with the 64-bit count in the w lanes, AOV sums), cleared or loaded from
// a resumed film at setup and read back by readFilm / finish. split: with the sobol sampler's
// sub-sequences (FrameParams::sobolSplits K > 1), K per pixel, sub-sequence k at K pixel + k: rgb
// its running mean, w its sample count (uint bits).
#define MCL_FILM_BUFFERS(F)      \
  F(mean, Pixel, Always)         \
  F(meanLo, Pixel, Always)       \
  F(m2, Pixel, Always)           \
  F(m2Lo, Pixel, Always)         \
  F(aovSum, AovsPerPixel, Aovs)  \
  F(split, SplitsPerPixel, Splits)

// The film's parts, counted from the list (the backends load, clear and read them part by part).
#define MCL_FILM_COUNT_ONE(name, per, need) +1
constexpr int kFilmBufferCount = 0 MCL_FILM_BUFFERS(MCL_FILM_COUNT_ONE);
#undef MCL_FILM_COUNT_ONE

// SCENE_TABLE(name, element type, dummy elements): the read-only scene tables, uploaded once per
// render and bound by name like the buffers above (render/scene_tables.h says where each comes
// from). A render without one (no textures, instances, vertex colours, ...) binds a dummy of that
// many elements instead: OpenCL has no empty buffers, and a stage binds every table it names
// whether or not it reads it (texels: one RGBA half texel). The BVH nodes are not a row: their
// type and upload follow the BVH layout.
#define MCL_SCENE_TABLES(S)          \
  S(tris, Triangle, 1)               \
  S(shading, TriangleShading, 1)     \
  S(normals, float4, 1)              \
  S(vertexColors, float4, 1)         \
  S(tangents, float4, 1)             \
  S(materials, Material, 1)          \
  S(emitters, Emitter, 1)            \
  S(textures, TextureDesc, 1)        \
  S(textureLevels, TextureLevel, 1)  \
  S(texels, ushort, 4)               \
  S(envMap, float4, 1)               \
  S(envCdf, float, 1)                \
  S(lightRecords, LightRecord, 1)    \
  S(instances, Instance, 1)

// What a render needs of these lists: the wave's size and what its integrator and options ask for.
struct WaveShape {
  std::uint64_t items = 1;   // wave items (pixel samples)
  std::uint64_t slots = 1;   // occlusion queries per item (IntegratorDesc::shadowSlots)
  std::uint64_t pixels = 1;  // image pixels (the film)
  bool bounce = false;       // the integrator traces BRDF rays within a wave (direct lighting)
  bool path = false;         // the integrator keeps path state (path tracing)
  bool aovs = false;         // first-hit AOVs are recorded
  std::uint64_t splits = 0;  // sobol sub-sequences with their own film accumulators (0: none)
  bool instances = false;    // the scene has a two-level BVH (hits carry their instance)
};

constexpr bool needed(Need need, const WaveShape& s) {
  return need == Need::Always || (need == Need::Bounce && s.bounce) || (need == Need::Path && s.path) ||
         (need == Need::Aovs && s.aovs) ||
         (need == Need::Splits && s.splits > 0) || (need == Need::Instances && s.instances) ||
         (need == Need::BounceInstances && s.instances && s.bounce);
}

// Elements of a buffer with this rule: its count when needed, else 1 (the dummy).
constexpr std::uint64_t bufferCount(Per per, Need need, const WaveShape& s) {
  if (!needed(need, s)) return 1;
  switch (per) {
    case Per::Item: return s.items;
    case Per::Slot: return s.items * s.slots;
    case Per::AovsPerItem: return MCL_AOV_VECTORS * s.items;
    case Per::Pixel: return s.pixels;
    case Per::AovsPerPixel: return MCL_AOV_VECTORS * s.pixels;
    case Per::SplitsPerPixel: return s.splits * s.pixels;
    case Per::One: return 1;
  }
  return 1;
}

constexpr bool perItem(Per per) { return per == Per::Item || per == Per::Slot || per == Per::AovsPerItem; }

// Bytes of the needed per-item buffers for one wave item (the wave's cost; dummies not counted).
constexpr std::uint64_t waveBytesPerItem(WaveShape s) {
  s.items = 1;
  std::uint64_t bytes = 0;
#define MCL_ITEM_BYTES(name, T, per, need) \
  if (needed(Need::need, s)) bytes += bufferCount(Per::per, Need::need, s) * sizeof(T);
  MCL_WAVE_BUFFERS(MCL_ITEM_BYTES)
#undef MCL_ITEM_BYTES
  return bytes;
}

// Bytes of the film per pixel on the device (and, read back, on the host).
constexpr std::uint64_t filmBytesPerPixel(bool aovs, std::uint64_t splits = 0) {
  WaveShape s;
  s.pixels = 1;
  s.aovs = aovs;
  s.splits = splits;
  std::uint64_t bytes = 0;
#define MCL_FILM_BYTES(name, per, need) \
  if (needed(Need::need, s)) bytes += bufferCount(Per::per, Need::need, s) * sizeof(float4);
  MCL_FILM_BUFFERS(MCL_FILM_BYTES)
#undef MCL_FILM_BYTES
  return bytes;
}

}  // namespace montecl
