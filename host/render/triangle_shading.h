// triangle_shading.h: the device's per-triangle attribute buffer (kernels/shared/types.h
// TriangleShading), in BVH order, from the scene's per-corner normals and texture coordinates; and
// the per-triangle unit geometric normals and areas (buildTriangleNormals).
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

// The vertex colours of bvh.triangles[i] (input triangle bvh.order[i], kHasColor) at out[3 i + k]
// (xyz; w 0), white for triangles without; empty when no triangle has any.
std::vector<float4> buildVertexColors(const Scene& scene, const Bvh& bvh);

// The corner tangents of bvh.triangles[i] (input triangle bvh.order[i], kHasTangents) at out[3 i + k]
// (xyz unit, w the handedness +1 or -1), zero for triangles without; empty when no triangle has any.
std::vector<float4> buildVertexTangents(const Scene& scene, const Bvh& bvh);

// normals[i] = (triangle_unit_normal, triangle_area_of) of tris[i]'s edges: the shade stages' geometric
// normal and emitter area, computed once with the kernels' own functions (kernels/shared/geometry.h;
// this library is built without FMA contraction, like the kernels), so every device reads the bits
// it would have computed itself. At least one entry (a zero one for an empty list).
std::vector<float4> buildTriangleNormals(const std::vector<Triangle>& tris);

}  // namespace montecl
