// builtin_scenes.h: small analytic scenes built in code, shared by `montecl conformance` and the
// tests: quads, a 2000-unit floor, the floor seen from above, and the floor beside a tall wall.
#pragma once
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace montecl {

// Appends the quad a, b, c, d (counter-clockwise seen from its front) as two triangles.
void addQuad(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, std::uint32_t material = 0);

// Adds the default material if there is none and recomputes the bounds.
void finishScene(Scene& s);

// The floor y = 0, 2000 units wide. Its two triangles' shared diagonal passes about 30 units from
// the origin: on triangles this large a ray through the diagonal can slip between the two (the
// intersection test is not watertight at a 1e-4 scale), so scenes keep test points away from it.
void addFloor(Scene& s, std::uint32_t material = 0);

// A UV sphere of `rings` latitude bands and `segments` longitude slices (quads split in two,
// triangles at the poles), counter-clockwise seen from outside. withNormals: each corner carries the
// exact sphere normal (kHasNormals), as a file's `vn` would; else flat.
void addUvSphere(Scene& s, glm::vec3 center, float radius, int rings, int segments, bool withNormals,
                 std::uint32_t material = 0);

// The floor, seen straight down from `height` above `at`; size x size pixels, spp samples.
Scene floorScene(glm::vec3 at, float height, float fovY, int size, int spp);

// The floor plus a wall x = 0 (y from 0 to 1000, z within +-1000), camera looking down at the
// floor around x = -0.5: AO there is 1/2 up to the wall's finite size (about 1e-3).
Scene wallScene(int size, int spp);

}  // namespace montecl
