// scene_tables.h: where each read-only scene table of a render (render/wave_buffers.h
// MCL_SCENE_TABLES) comes from: views of the StageInputs arrays, each replaced by its dummy when
// empty, so that both backends upload or bind them all by iterating the list. Reads StageInputs;
// computes the triangle normals (the one table the inputs do not hold).
#pragma once
#include <vector>

#include "render/stage_runner.h"

namespace montecl {

// The tables of one render: each member points at its source array or at the table's dummy,
// never at an empty array. The views point into the StageInputs (which must outlive them) and,
// for normals, into ownNormals: not copyable, so that nothing points into a copy.
struct SceneTables {
#define MCL_SCENE_TABLE_VIEW(name, T, dummy) const std::vector<T>* name = nullptr;
  MCL_SCENE_TABLES(MCL_SCENE_TABLE_VIEW)
#undef MCL_SCENE_TABLE_VIEW
  // Per BVH-ordered triangle: its unit geometric normal, w its area (buildTriangleNormals).
  std::vector<float4> ownNormals;

  SceneTables() = default;
  SceneTables(const SceneTables&) = delete;
  SceneTables& operator=(const SceneTables&) = delete;
  // Points every table at in's arrays: tris (in.triangles, else the BVH's), shading, vertexColors
  // and tangents (per triangle or corner, BVH order), materials, emitters, the texture tables
  // (in.textures), envMap and envCdf, lightRecords, the BVH's instances; normals computed.
  void view(const StageInputs& in);
  // Lets go of every view and of the normals.
  void release();
};

}  // namespace montecl
