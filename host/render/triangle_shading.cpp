// triangle_shading.cpp: fills TriangleShading in BVH order from SceneTriangle::n/uv/attributes, the
// vertex colours and corner tangents (Scene::vertexColors, vertexTangents) in BVH order, and the
// per-triangle unit geometric normals and areas.
#include "render/triangle_shading.h"

#include "kernels/shared/geometry.h"

#include <algorithm>
#include <cmath>

namespace montecl {
namespace {

glm::vec3 unitOrZero(const glm::vec3& n) {
  const float len = glm::length(n);
  return len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f);
}

// out[3 i + k] = device(side[3 bvh.order[i] + k]) for the triangles with `flag` whose corners side
// holds, fill for the others; empty when no triangle has them (the renderer binds a dummy).
template <class T, class Device>
std::vector<float4> cornersInBvhOrder(const Scene& scene, const Bvh& bvh, std::uint8_t flag, const std::vector<T>& side,
                                      float4 fill, Device device) {
  const auto has = [&](std::uint32_t k) {
    return (scene.triangles[k].attributes & flag) && 3u * std::size_t(k) + 2u < side.size();
  };
  if (!std::any_of(bvh.order.begin(), bvh.order.end(), has)) return {};
  std::vector<float4> out(3 * bvh.order.size(), fill);
  for (std::size_t i = 0; i < bvh.order.size(); ++i)
    if (has(bvh.order[i]))
      for (std::size_t k = 0; k < 3; ++k) out[3 * i + k] = device(side[3 * std::size_t(bvh.order[i]) + k]);
  return out;
}

}  // namespace

std::vector<TriangleShading> buildTriangleShading(const std::vector<SceneTriangle>& tris, const Bvh& bvh) {
  const bool any = std::any_of(bvh.order.begin(), bvh.order.end(),
                               [&](std::uint32_t k) { return tris[k].attributes != 0; });
  if (!any) return std::vector<TriangleShading>(1, TriangleShading{});
  std::vector<TriangleShading> out(bvh.order.size(), TriangleShading{});
  for (std::size_t i = 0; i < bvh.order.size(); ++i) {
    const SceneTriangle& t = tris[bvh.order[i]];
    TriangleShading& s = out[i];
    glm::vec4* corners[3] = {&s.n0, &s.n1, &s.n2};
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 n = (t.attributes & kHasNormals) ? unitOrZero(t.n[k]) : glm::vec3(0.0f);
      const float u = (t.attributes & kHasUv) ? t.uv[k].x : 0.0f;
      *corners[k] = glm::vec4(n, u);
    }
    if (t.attributes & kHasUv) s.tv = glm::vec4(t.uv[0].y, t.uv[1].y, t.uv[2].y, 0.0f);
  }
  return out;
}

std::vector<float4> buildVertexColors(const Scene& scene, const Bvh& bvh) {
  return cornersInBvhOrder(scene, bvh, kHasColor, scene.vertexColors, float4(1.0f, 1.0f, 1.0f, 0.0f),
                           [](const glm::vec3& c) { return float4(c, 0.0f); });
}

std::vector<float4> buildVertexTangents(const Scene& scene, const Bvh& bvh) {
  return cornersInBvhOrder(scene, bvh, kHasTangents, scene.vertexTangents, float4(0.0f),
                           [](const glm::vec4& t) { return float4(t); });
}

std::vector<float4> buildTriangleNormals(const std::vector<Triangle>& tris) {
  std::vector<float4> out(std::max<std::size_t>(1, tris.size()), float4(0.0f));
  for (std::size_t i = 0; i < tris.size(); ++i) {
    const float3 e1 = xyz(tris[i].e1), e2 = xyz(tris[i].e2);
    out[i] = float4(triangle_unit_normal(e1, e2), triangle_area_of(e1, e2));
  }
  return out;
}

}  // namespace montecl
