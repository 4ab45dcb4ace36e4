// bench_alpha.cpp: the bench's cut-out test shared by its tracers (bench_alpha.h).
#include "bench/bench_alpha.h"

#include "render/device_materials.h"
#include "render/triangle_shading.h"

namespace montecl {

bool BenchAlpha::exists(std::uint32_t tri, float u, float v, const float3& org, const float3& dir) const {
  if (!tested[tri]) return true;
  return alpha_hit_exists(&host, tris, slot[tri], u, v, org, dir) != 0;
}

std::unique_ptr<BenchAlpha> makeBenchAlpha(const Scene& scene, Bvh& bvh, std::vector<std::string>& warnings) {
  auto a = std::make_unique<BenchAlpha>();
  a->scene = &scene;
  if (sceneHasTextures(scene)) a->textures = loadSceneTextures(scene, kDefaultTextureBudget, warnings);
  if (!anyAlphaTested(scene.materials, &a->textures)) return nullptr;
  bvh.triangles = alphaFlaggedTriangles(bvh.triangles, scene.materials, &a->textures);
  a->tris = bvh.triangles.data();
  a->materials = deviceMaterials(scene.materials, &a->textures);
  a->shading = buildTriangleShading(scene.triangles, bvh);
  a->tested.resize(scene.triangles.size());
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    a->tested[i] = materialAlphaTested(scene.materials, &a->textures, scene.triangles[i].material);
    a->testedCount += a->tested[i];
  }
  a->slot.assign(scene.triangles.size(), 0u);
  for (std::size_t i = bvh.order.size(); i-- > 0;) a->slot[bvh.order[i]] = std::uint32_t(i);  // the first slot
  a->host = make_alpha_scene(a->materials.data(), a->shading.data(),
                             make_texture_tables(a->textures.textures.data(), a->textures.levels.data(),
                                                 a->textures.texels.data()));
  return a;
}

}  // namespace montecl
