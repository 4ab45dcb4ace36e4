// scenes.h: the conformance set: small analytic scenes built in code (an open floor, a floor
// beside a wall, a tilted polygon light over a floor with an occluder, the same with a smooth-shaded
// sphere, the same with a textured floor and a cut-out occluder) rendered with every integrator and sampling strategy, plus the Cornell box from the
// shared scenes when present.
// Ported from tests/test_scenes.h and tests/test_direct.cpp so that `montecl conformance` runs
// without the test sources.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "texture/scene_textures.h"

namespace montecl {

struct ConformanceCase {
  std::string name;  // e.g. "wall/ao-uniform"
  Scene scene;
  // Decoded textures of the scene's materials, built in memory (no image files: the set runs where
  // OpenImageIO is not installed); null when the scene has none.
  std::shared_ptr<const SceneTextures> textures;
  bool aovs = false;  // also record the first-hit AOVs (record_aov, accumulate_aov) and compare them
};

struct ConformanceSetOptions {
  int size = 16;        // width = height of the analytic scenes
  int spp = 8;
  int cornellSize = 32;  // Cornell box image size
  int cornellSpp = 4;
  std::string cornellPath;  // scene.json of the Cornell box; empty or missing: skipped
};

// The cases; `skipped` receives one line per case that could not be built (missing scene file).
std::vector<ConformanceCase> conformanceSet(const ConformanceSetOptions& options, std::vector<std::string>& skipped);

// Default location of the shared Cornell box: <source dir>/../shared/scenes/cornell-box/scene.json.
std::string defaultCornellPath();

}  // namespace montecl
