// terrain.h: procedural benchmark geometry: a seeded, tessellated height-field terrain with exactly
// the requested number of triangles, written as OBJ (and optionally a scene file that frames it,
// with a small emissive quad above it so shadow rays are exercised).
#pragma once
#include <cstdint>
#include <string>

namespace montecl {

struct TerrainOptions {
  std::uint64_t triangles = 1000;  // exact triangle count of the OBJ (>= 1)
  std::uint32_t seed = 0;
  float size = 100.0f;             // the terrain spans [-size/2, size/2] in x and z
};

// Writes the terrain OBJ atomically. Returns the number of triangles written (== options.triangles).
std::uint64_t writeTerrainObj(const std::string& objPath, const TerrainOptions& options);

// Writes a scene file next to nothing else: it references objPath (relative to the scene's folder)
// and a light OBJ it writes beside the scene (<scene stem>-light.obj), with a camera of the given
// resolution and ao_distance = size / 20.
void writeTerrainScene(const std::string& scenePath, const std::string& objPath, const TerrainOptions& options,
                       int width, int height);

}  // namespace montecl
