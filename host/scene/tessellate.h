// tessellate.h: round shapes as triangles for the scene readers (pbrt's sphere and disk, Mitsuba's
// sphere and disk): object-space triangles with exact corner normals and UVs.
#pragma once
#include <vector>

#include "scene/scene.h"

namespace montecl {

// Sphere and disk tessellation: a sphere gets kSphereSegments steps in longitude and half as
// many in latitude, a disk kSphereSegments steps around. A facet spans at most 2 pi / 128 in
// both directions, so it lies within r (1 - cos(sqrt(2) pi / 128)) = 6.0e-4 r of the exact
// surface (the sphere's area comes out 5.0e-4 short: tests/test_pbrt_parser.cpp), and every
// corner carries the exact normal, so shading is round.
constexpr int kSphereSegments = 128;

// A sphere of radius r about the origin, outward, poles on z (v = 0 at -z, u = phi / 2 pi from +x).
void tessellateSphere(double r, std::vector<SceneTriangle>& out);

// A disk of radius r (a ring from ri) at z = h, front +z; uv: u = phi / 2 pi, v = (r - rho) / (r - ri).
void tessellateDisk(double r, double ri, double h, std::vector<SceneTriangle>& out);

}  // namespace montecl
