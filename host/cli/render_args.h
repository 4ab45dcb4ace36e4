// render_args.h: the options of `montecl render` as parsed (RenderArgs), and how they change the
// loaded scene (applyOverrides: settings, environment; viewCamera: the camera of one view, its size).
// Reads no files but --env's map.
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "cli/render_views.h"
#include "job/job.h"
#include "scene/scene.h"

namespace montecl {

struct RenderArgs {
  std::string scene, output, device;
  std::map<std::string, std::string> settings;  // render setting key -> its option's text (scene/render_settings.h)
  std::string bvhLayout = "auto";
  float splitBudget = BvhBuildOptions{}.splitBudget;  // --split-budget
  std::optional<int> width, height;
  std::optional<double> textureBudgetMiB;  // --texture-budget; unset: automatic
  std::uint64_t waveSize = 0;
  std::uint32_t firstSample = 0;
  double targetError = 0.0, timeLimit = 0.0;
  int minSpp = 16, maxSpp = 1024;
  std::vector<std::string> aovs;
  std::string env, view;            // --env R,G,B | FILE; --view SIDE
  CameraRequest cameras;            // --camera N | N,M,... | all: the file's cameras (cli/render_views.h)
  std::optional<unsigned> gltfScene;  // --scene N: a glTF model's scene N (loadScene)
  std::optional<float> fov;         // --fov DEG
  std::string lookFrom, lookAt;     // --look-from X,Y,Z; --look-at X,Y,Z
  float envScale = 1.0f, envRotate = 0.0f;
  std::size_t workGroupSize = 0;
  unsigned lanes = 0;  // packet stages' width W (0: the device's)
  bool quiet = false, verbose = false, overwrite = false, profile = false, noFuse = false;
  jobs::JobArgs job;  // MPI split, --checkpoint, --resume (job/job.h)
};

// The command line's changes to the scene but its camera: render settings, the environment.
void applyOverrides(const RenderArgs& a, Scene& scene);

// The camera of one view: the scene's, or the file's camera `fileCamera` (one of --camera's,
// resolveCameras), then --width / --height, --view, --look-from / --look-at, --fov. Throws
// InputError "--option: <problem>" for a camera they make unusable.
Camera viewCamera(const RenderArgs& a, const Scene& scene, std::optional<unsigned> fileCamera);

}  // namespace montecl
