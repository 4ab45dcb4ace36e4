// render_views.h: which views one `montecl render` renders, and the name each image gets. --camera
// takes N, a list N,M,... or all (every perspective camera of a glTF file); with more than one view
// the output is a pattern whose {camera} becomes each camera's number (out_{camera}.png ->
// out_0.png, out_1.png, ...), as a Blender frame pattern names each frame. Reads no files.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace montecl {

// --camera as written: none (the scene's camera), all, or the cameras listed, in the order given.
struct CameraRequest {
  bool given = false, all = false;
  std::vector<unsigned> list;
  // Whether this can be more than one view (all, or a list of two or more): the output must then
  // be a pattern, known before the file is read.
  bool batch() const { return all || list.size() > 1; }
};

// The placeholder an output pattern holds: "{camera}".
extern const char* const kCameraPlaceholder;

// "" when text is a --camera value (N, N,M,... without repeats, or all), else the rule it breaks
// (a CLI11 validator's message).
std::string cameraRequestProblem(const std::string& text);
CameraRequest parseCameraRequest(const std::string& text);  // text passed cameraRequestProblem

// Refuses (InputError "-o: ...") an output that cannot name the views asked for, before the scene
// is read: a batch needs {camera} in the name; {camera} without --camera names nothing.
void checkOutputPattern(const std::string& output, const CameraRequest& cameras);

// The cameras to render, in order, once the file's camera count is known; InputError "--camera:
// ..." for one out of range or all of a file without cameras. Empty when --camera was not given.
std::vector<unsigned> resolveCameras(const CameraRequest& cameras, std::size_t fileCameras, const std::string& scenePath);

// The pattern with every {camera} replaced by camera's number.
std::string expandOutputPattern(const std::string& pattern, unsigned camera);

}  // namespace montecl
