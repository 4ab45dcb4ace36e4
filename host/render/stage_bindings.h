// stage_bindings.h: what the stage table's argument names (kernels/shared/stage_table.h) refer to
// on the host. StageBindings holds every buffer and per-wave value a stage can name, as Array<T>:
// T* on the host backend, a typed cl::Buffer on OpenCL. From the table it generates, per stage:
// the host call (hostStageArgs: fills <stage>_args from the bindings) and the OpenCL argument
// binding (bindStageArgs: frame, then each argument by name). A table argument whose name is not
// a member here, or whose type the member cannot convert to, does not compile in either backend.
#pragma once
#include <cstdint>
#include <type_traits>

#include "cl/cl_session.h"
#include "kernels/stages/stages.h"
#include "render/wave_buffers.h"

namespace montecl {

enum class Stage {
#define MCL_STAGE_ENUM(stage) stage,
  MCL_STAGES(MCL_STAGE_ENUM)
#undef MCL_STAGE_ENUM
};

// The stage's kernel name in kernels/montecl.cl.
inline const char* stageName(Stage s) {
  static const char* const names[] = {
#define MCL_STAGE_NAME(stage) #stage,
      MCL_STAGES(MCL_STAGE_NAME)
#undef MCL_STAGE_NAME
  };
  return names[int(s)];
}
// True for a fused stage (kernels/stages/wave_fused.h): a work item runs a group of W C items through
// every stage of a wave.
inline bool stageIsFused(Stage s) { return s == Stage::wave_ao || s == Stage::wave_direct || s == Stage::wave_path; }
// True for a stage whose OpenCL kernel runs W consecutive items per work item (launched over
// ceil(items / W) work items): every stage but the fused ones (kernels/shared/stage_table.h).
inline bool stageRunsPackets(Stage s) { return !stageIsFused(s); }
#define MCL_STAGE_COUNT_ONE(stage) +1
constexpr int kStageCount = 0 MCL_STAGES(MCL_STAGE_COUNT_ONE);
#undef MCL_STAGE_COUNT_ONE

// Which rays a stage reads: Bounce binds its `rays`, `hits` and `hitInstances` to `bounce`,
// `bounceHits` and `bounceHitInstances` (intersect of direct lighting's BRDF rays).
enum class RayInput { Camera, Bounce };

template <template <class> class Array>
struct StageBindings {
  Array<FrameParams> frame;
  // Scene, uploaded once: the BVH nodes (their type follows the layout) and the read-only tables
  // (render/wave_buffers.h MCL_SCENE_TABLES, where each is described).
  Array<BvhTraversalNode> nodes;
#define MCL_BINDING_TABLE(name, T, dummy) Array<const T> name;
  MCL_SCENE_TABLES(MCL_BINDING_TABLE)
#undef MCL_BINDING_TABLE
  Array<uint> active;  // the active-pixel list
  // Per wave item, the counters and the film (render/wave_buffers.h, where each is described).
#define MCL_BINDING_BUFFER(name, T, per, need) Array<T> name;
#define MCL_BINDING_COUNTER(name) Array<uint> name;
#define MCL_BINDING_FILM(name, per, need) Array<float4> name;
  MCL_WAVE_BUFFERS(MCL_BINDING_BUFFER)
  MCL_WAVE_COUNTERS(MCL_BINDING_COUNTER)
  MCL_FILM_BUFFERS(MCL_BINDING_FILM)
#undef MCL_BINDING_BUFFER
#undef MCL_BINDING_COUNTER
#undef MCL_BINDING_FILM
  // Per wave.
  ulong waveStart = 0;
  uint waveCount = 0;
  uint pathBounce = 0;  // path tracing: the bounce being shaded (0: camera rays)

  StageBindings forRays(RayInput set) const {
    StageBindings b = *this;
    if (set == RayInput::Bounce) {
      b.rays = bounce;
      b.hits = bounceHits;
      b.hitInstances = bounceHitInstances;
    }
    return b;
  }
};

// --- host backend: Array<T> = T* ---------------------------------------------------------------
template <class T>
using HostArray = T*;
using HostBindings = StageBindings<HostArray>;

// Calls body(args) with the stage's <stage>_args filled from b (frame first, then by name).
template <class Body>
void withHostStageArgs(Stage s, const HostBindings& b, const Body& body) {
#define MCL_HOST_ARG(type, name) , b.name
#define MCL_HOST_CASE(stage)                                   \
  case Stage::stage: {                                         \
    const stage##_args args = {b.frame MCL_ARGS_##stage(MCL_HOST_ARG)}; \
    body(args);                                                \
    return;                                                    \
  }
  switch (s) { MCL_STAGES(MCL_HOST_CASE) }
#undef MCL_HOST_CASE
#undef MCL_HOST_ARG
}

// --- OpenCL: Array<T> = ClArray<T>, a buffer of T ----------------------------------------------
template <class T>
struct ClArray {
  cl::Buffer buffer;
};
using ClBindings = StageBindings<ClArray>;

namespace detail {
// A buffer argument: the table's pointer type must accept a T*.
template <class Param, class T>
void setStageArg(cl::Kernel& k, cl_uint index, const ClArray<T>& a) {
  static_assert(std::is_pointer<Param>::value && std::is_convertible<T*, Param>::value,
                "stage table argument type and StageBindings member disagree");
  k.setArg(index, a.buffer);
}
// A value argument: the same type on both sides.
template <class Param, class T>
void setStageArg(cl::Kernel& k, cl_uint index, const T& value) {
  static_assert(std::is_same<Param, T>::value, "stage table value type and StageBindings member disagree");
  k.setArg(index, value);
}
}  // namespace detail

// Sets every argument of stage s's kernel from b: frame, then the table's, by name.
inline void bindStageArgs(cl::Kernel& k, Stage s, const ClBindings& b) {
  cl_uint index = 0;
  k.setArg(index++, b.frame.buffer);
#define MCL_CL_ARG(type, name) detail::setStageArg<type>(k, index++, b.name);
#define MCL_CL_CASE(stage)        \
  case Stage::stage:              \
    MCL_ARGS_##stage(MCL_CL_ARG) \
    return;
  switch (s) { MCL_STAGES(MCL_CL_CASE) }
#undef MCL_CL_CASE
#undef MCL_CL_ARG
}

}  // namespace montecl
