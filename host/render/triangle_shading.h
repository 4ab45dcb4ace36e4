// triangle_shading.h: the device's per-triangle attribute buffer (kernels/shared/types.h
// TriangleShading), in BVH order, from the scene's per-corner normals and texture coordinates.
#pragma once
#include <vector>

#include "bvh/bvh.h"
#include "scene/scene.h"

namespace montecl {

// shading[i] holds the attributes of bvh.triangles[i] (input triangle bvh.order[i]): unit corner
// normals (kHasNormals; zero or non-finite ones stay as they are and the kernels fall back to the
// geometric normal) and corner UVs (kHasUv), zero where a triangle lacks them. When no triangle
// has attributes, one zero entry (never read: Triangle::e2.w holds no flag), so such scenes pay
// 64 bytes, not 64 per triangle.
std::vector<TriangleShading> buildTriangleShading(const std::vector<SceneTriangle>& tris, const Bvh& bvh);

}  // namespace montecl
