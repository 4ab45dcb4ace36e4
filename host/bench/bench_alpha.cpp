// bench_alpha.cpp: the bench's cut-out test shared by its tracers (bench_alpha.h).
#include "bench/bench_alpha.h"

#include "render/device_materials.h"
#include "render/triangle_shading.h"

namespace montecl {

bool BenchAlpha::exists(std::uint32_t tri, float u, float v) const {
  if (!tested[tri]) return true;
  const SceneTriangle& t = scene->triangles[tri];
  const Material& m = materials[t.material];
  float uu = 0.0f, vv = 0.0f;
  if (t.attributes & kHasUv) {  // as surface_uv (surface_texture.h)
    const float w = 1.0f - u - v;
    uu = t.uv[0].x * w + t.uv[1].x * u + t.uv[2].x * v;
    vv = t.uv[0].y * w + t.uv[1].y * u + t.uv[2].y * v;
  }
  return alpha_value(host.tex, m, uu, vv) >= m.alpha.y;
}

std::unique_ptr<BenchAlpha> makeBenchAlpha(const Scene& scene, Bvh& bvh, std::vector<std::string>& warnings) {
  if (!sceneHasTextures(scene)) return nullptr;
  auto a = std::make_unique<BenchAlpha>();
  a->scene = &scene;
  a->textures = loadSceneTextures(scene, kDefaultTextureBudget, warnings);
  if (!a->textures.anyAlpha()) return nullptr;
  bvh.triangles = alphaFlaggedTriangles(bvh.triangles, a->textures);
  a->materials = deviceMaterials(scene.materials, &a->textures);
  a->shading = buildTriangleShading(scene.triangles, bvh);
  a->tested.resize(scene.triangles.size());
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    const std::uint32_t m = scene.triangles[i].material;
    a->tested[i] = m < a->textures.materials.size() && a->textures.materials[m].alpha != MCL_NO_TEXTURE;
    a->testedCount += a->tested[i];
  }
  a->host = make_alpha_scene(a->materials.data(), a->shading.data(),
                             make_texture_tables(a->textures.textures.data(), a->textures.levels.data(),
                                                 a->textures.texels.data()));
  return a;
}

}  // namespace montecl
