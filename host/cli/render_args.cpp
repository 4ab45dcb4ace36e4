// render_args.cpp: applyOverrides and viewCamera (render_args.h): the command line's settings,
// environment and camera applied to the loaded scene.
#include "cli/render_args.h"

#include <cmath>
#include <cstdio>

#include "scene/camera_basis.h"
#include "scene/environment_key.h"
#include "scene/load_util.h"
#include "scene/render_settings.h"
#include "util/errors.h"

namespace montecl {

namespace {

// X,Y,Z of --look-from or --look-at: three finite numbers.
glm::vec3 cameraPointOption(const char* option, const std::string& text) {
  float v[3];
  char end = 0;
  if (std::sscanf(text.c_str(), "%f,%f,%f%c", &v[0], &v[1], &v[2], &end) != 3 || !std::isfinite(v[0]) ||
      !std::isfinite(v[1]) || !std::isfinite(v[2]))
    throwInputError(option, "", "'" + oneLine(text, 60) + "' is not a point X,Y,Z (three finite numbers, e.g. 0,1,5)");
  return glm::vec3(v[0], v[1], v[2]);
}

}  // namespace

void applyOverrides(const RenderArgs& a, Scene& scene) {
  for (const RenderSetting& s : renderSettings()) {
    const auto it = a.settings.find(s.key);
    if (it != a.settings.end()) setFromText(s, it->second, scene.render);
  }
  // Adaptive sampling stops each pixel on its estimated error, or shares samples out by it: under
  // sobol that needs the sub-sequences (var/n overstates it 30-100x there), so --target-error and
  // --adaptive (render.adaptive) ask for them.
  if (a.targetError > 0.0 || scene.render.adaptive) scene.render.errorEstimate = true;
  // The command line's environment replaces the scene's.
  if (!a.env.empty()) {
    scene.environment = environmentFromOption(a.env, a.envScale, a.envRotate);
    if (!scene.environment.file.empty()) scene.inputFiles.push_back(scene.environment.file);
  }
}

Camera viewCamera(const RenderArgs& a, const Scene& scene, std::optional<unsigned> fileCamera) {
  // The file's camera before the size: --width and --height still set it.
  Camera camera = fileCamera ? scene.fileCameras.at(*fileCamera) : scene.camera;
  if (a.width) camera.width = *a.width;
  if (a.height) camera.height = *a.height;
  // --view frames the model from that side.
  if (!a.view.empty()) {
    if (!isViewName(a.view)) throwInputError("--view", "", "unknown side '" + a.view + "' (known: " + viewNames() + ")");
    camera = defaultCamera(scene.boundsMin, scene.boundsMax, camera.width, camera.height, a.view);
  }
  // Then the camera chosen above moved, turned or zoomed.
  if (!a.lookFrom.empty()) camera.position = cameraPointOption("--look-from", a.lookFrom);
  if (!a.lookAt.empty()) camera.target = cameraPointOption("--look-at", a.lookAt);
  if (a.fov) camera.fovY = *a.fov;
  if (!a.lookFrom.empty() || !a.lookAt.empty() || a.fov) {
    const CameraProblem p = cameraBasisProblem(camera);
    if (!p.empty())
      throwInputError(a.lookFrom.empty() && a.lookAt.empty() ? "--fov" : "--look-from/--look-at", "",
                      "the camera is unusable: " + p.key + " " + p.problem);
  }
  return camera;
}

}  // namespace montecl
