// cmd_generate.cpp: `montecl generate terrain --triangles N -o FILE.obj [--seed S] [--scene FILE.json]`:
// procedural benchmark geometry (host/bench/terrain.h) with exactly N triangles.
#include <iostream>

#include "bench/terrain.h"
#include "cli/commands.h"
#include "cli/validators.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace montecl {

void addGenerateCommand(CLI::App& app, int& exitCode) {
  CLI::App* gen = app.add_subcommand("generate", "Generate procedural benchmark geometry");
  gen->require_subcommand(1);
  struct Args {
    TerrainOptions terrain;
    std::string output, scene;
    int width = 512, height = 512;
  };
  auto a = std::make_shared<Args>();
  CLI::App* t = gen->add_subcommand("terrain", "Tessellated height-field terrain with exactly N triangles");
  t->add_option("--triangles", a->terrain.triangles, "Triangle count (1k to 10M is the intended range)")
      ->required()
      ->check(CLI::Range(std::uint64_t(1), std::uint64_t(100000000)));
  t->add_option("-o,--output", a->output, "Output OBJ file")->required();
  t->add_option("--seed", a->terrain.seed, "Random seed of the height field");
  t->add_option("--scene", a->scene, "Also write a scene file (.json) framing the terrain, with an emissive quad");
  t->add_option("--width", a->width, "Image width in the scene file")->check(positiveInteger(kMaxImageSide));
  t->add_option("--height", a->height, "Image height in the scene file")->check(positiveInteger(kMaxImageSide));
  t->callback([a, &exitCode]() {
    std::uint64_t n = writeTerrainObj(a->output, a->terrain);
    if (!a->scene.empty()) writeTerrainScene(a->scene, a->output, a->terrain, a->width, a->height);
    std::cout << "wrote " << a->output << ": " << n << " triangles"
              << (a->scene.empty() ? "" : ", scene " + a->scene) << "\n";
    exitCode = kExitOk;
  });
}

}  // namespace montecl
