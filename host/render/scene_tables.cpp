// scene_tables.cpp: the sources of the read-only scene tables and their dummies (MCL_SCENE_TABLES).
#include "render/scene_tables.h"

#include <stdexcept>

#include "render/triangle_shading.h"

namespace montecl {

void SceneTables::view(const StageInputs& in) {
  release();  // (so that a table this function forgets is caught below, on every render)
  static const SceneTextures kNoTextures;
  const SceneTextures& tex = in.textures ? *in.textures : kNoTextures;
  ownNormals = buildTriangleNormals(in.bvh->triangles);
  tris = in.triangles.empty() ? &in.bvh->triangles : &in.triangles;
  shading = &in.shading;
  normals = &ownNormals;
  vertexColors = &in.vertexColors;
  tangents = &in.tangents;
  materials = &in.materials;
  emitters = &in.emitters;
  textures = &tex.textures;
  textureLevels = &tex.levels;
  texels = &tex.texels;
  envMap = &in.envMap;
  envCdf = &in.envCdf;
  lightRecords = &in.lightRecords;
  instances = &in.bvh->instances;
  // An empty table binds its dummy (zeros, never read by a stage: the frame's counts say so).
#define MCL_SCENE_TABLE_DUMMY(name, T, dummy)                                          \
  {                                                                                    \
    static const std::vector<T> kDummy(dummy);                                         \
    if (!name) throw std::logic_error("scene table " #name " has no source in SceneTables::view"); \
    if (name->empty()) name = &kDummy;                                                 \
  }
  MCL_SCENE_TABLES(MCL_SCENE_TABLE_DUMMY)
#undef MCL_SCENE_TABLE_DUMMY
}

void SceneTables::release() {
#define MCL_SCENE_TABLE_RELEASE(name, T, dummy) name = nullptr;
  MCL_SCENE_TABLES(MCL_SCENE_TABLE_RELEASE)
#undef MCL_SCENE_TABLE_RELEASE
  ownNormals = {};
}

}  // namespace montecl
