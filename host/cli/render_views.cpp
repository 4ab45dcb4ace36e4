// render_views.cpp: --camera's views and the output pattern that names their images (see
// render_views.h).
#include "cli/render_views.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>

#include "scene/load_util.h"
#include "util/errors.h"

namespace montecl {

const char* const kCameraPlaceholder = "{camera}";

namespace {

bool hasPlaceholder(const std::string& s) { return s.find(kCameraPlaceholder) != std::string::npos; }

// The comma-separated items of text ("" items kept, so "1,,2" is refused).
std::vector<std::string> items(const std::string& text) {
  std::vector<std::string> out;
  std::size_t from = 0;
  for (;;) {
    const std::size_t comma = text.find(',', from);
    out.push_back(text.substr(from, comma == std::string::npos ? std::string::npos : comma - from));
    if (comma == std::string::npos) return out;
    from = comma + 1;
  }
}

bool cameraNumber(const std::string& s, unsigned& v) {
  if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return false;
  v = unsigned(std::strtoul(s.c_str(), nullptr, 10));
  return true;
}

}  // namespace

std::string cameraRequestProblem(const std::string& text) {
  if (text == "all") return "";
  std::vector<unsigned> seen;
  for (const std::string& item : items(text)) {
    unsigned v = 0;
    if (!cameraNumber(item, v))
      return "must be a camera number (from 0), a list of them (0,2,5) or all, got '" + oneLine(text, 60) + "'";
    if (std::find(seen.begin(), seen.end(), v) != seen.end())
      return "camera " + item + " is listed twice in '" + oneLine(text, 60) + "'";
    seen.push_back(v);
  }
  return "";
}

CameraRequest parseCameraRequest(const std::string& text) {
  CameraRequest r;
  r.given = true;
  r.all = text == "all";
  if (!r.all)
    for (const std::string& item : items(text)) {
      unsigned v = 0;
      if (cameraNumber(item, v)) r.list.push_back(v);
    }
  return r;
}

void checkOutputPattern(const std::string& output, const CameraRequest& cameras) {
  if (cameras.batch() && !output.empty() && !hasPlaceholder(output))
    throwInputError("-o", "",
                    "'" + oneLine(output, 80) + "' has no {camera}: --camera " +
                        (cameras.all ? std::string("all") : std::string("with several cameras")) +
                        " writes one image per camera, named by a pattern such as out_{camera}.png");
  if (!cameras.given && hasPlaceholder(output))
    throwInputError("-o", "",
                    "'" + oneLine(output, 80) + "' holds {camera} but no --camera was given (--camera all renders "
                    "every camera of the file, --camera 0,2 those listed)");
}

std::vector<unsigned> resolveCameras(const CameraRequest& cameras, std::size_t fileCameras, const std::string& scenePath) {
  if (!cameras.given) return {};
  const std::string has = oneLine(scenePath) + " has " + std::to_string(fileCameras) +
                          (fileCameras == 1 ? " camera" : " cameras") +
                          " (a glTF file's perspective cameras, from 0; --view or --look-from frame other models)";
  if (cameras.all) {
    if (fileCameras == 0) throwInputError("--camera", "", "all: no camera to render: " + has);
    std::vector<unsigned> every(fileCameras);
    for (std::size_t i = 0; i < fileCameras; ++i) every[i] = unsigned(i);
    return every;
  }
  for (unsigned c : cameras.list)
    if (c >= fileCameras) throwInputError("--camera", "", "camera " + std::to_string(c) + " out of range: " + has);
  return cameras.list;
}

std::string expandOutputPattern(const std::string& pattern, unsigned camera) {
  std::string out = pattern;
  const std::string number = std::to_string(camera), key = kCameraPlaceholder;
  for (std::size_t at = out.find(key); at != std::string::npos; at = out.find(key, at + number.size()))
    out.replace(at, key.size(), number);
  return out;
}

}  // namespace montecl
