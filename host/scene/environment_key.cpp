// environment_key.cpp: parses and checks the scene file's "environment" key (environment_key.h).
#include "scene/environment_key.h"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "util/errors.h"

namespace montecl {
namespace {

using nlohmann::json;

float number(const std::string& file, const json& v, const std::string& where) {
  if (!v.is_number()) throwInputError(file, where, std::string("expected a number, got ") + v.type_name());
  const float f = v.get<float>();
  if (!std::isfinite(f)) throwInputError(file, where, "number out of float range");
  return f;
}

// A map file must be a readable regular file (it is decoded at render time).
void checkMapFile(const std::string& file, const std::string& from, const std::string& where) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) throwInputError(from, where, "cannot open '" + file + "': " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throwInputError(from, where, "cannot open '" + file + "': not a regular file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throwInputError(from, where, "cannot open '" + file + "': " + std::strerror(errno));
}

}  // namespace

EnvironmentDesc environmentFromOption(const std::string& text, float scale, float rotateYDegrees) {
  EnvironmentDesc env;
  // "none": no environment at all (a bare model's default sky off; the scene's own lights only).
  if (text == "none") return env;
  env.enabled = true;
  if (!(std::isfinite(scale) && scale >= 0.0f)) throwInputError("--env-scale", "", "must be finite and >= 0");
  if (!std::isfinite(rotateYDegrees)) throwInputError("--env-rotate", "", "must be finite");
  env.scale = scale;
  env.rotateYDegrees = rotateYDegrees;
  // "R,G,B": three numbers; anything else names a map file.
  float rgb[3];
  char end = 0;
  if (std::sscanf(text.c_str(), "%f,%f,%f%c", &rgb[0], &rgb[1], &rgb[2], &end) == 3) {
    for (int c = 0; c < 3; ++c)
      if (!(std::isfinite(rgb[c]) && rgb[c] >= 0.0f)) throwInputError("--env", "", "radiance components must be finite and >= 0");
    env.radiance = glm::vec3(rgb[0], rgb[1], rgb[2]);
  } else {
    if (text.empty()) throwInputError("--env", "", "expected R,G,B or an environment map file");
    // Numbers that are not three (1,1 or 0.5), or a list with a comma (1,x,1), are a constant
    // mistyped rather than a file name (unless such a file exists): say the forms.
    const bool numeric = text.find_first_not_of("0123456789.,+-eE ") == std::string::npos;
    if ((numeric || text.find(',') != std::string::npos) && !std::filesystem::exists(text))
      throwInputError("--env", "", "'" + text + "' is neither R,G,B (three radiances, e.g. 1,1,1) nor an "
                                  "environment map file (.exr, .hdr, ...); none turns the environment off");
    env.file = std::filesystem::path(text).lexically_normal().string();
    checkMapFile(env.file, "--env", "");
  }
  const glm::vec3 total = env.radiance * env.scale;
  if (!(std::isfinite(total.x) && std::isfinite(total.y) && std::isfinite(total.z)))
    throwInputError("--env-scale", "", "radiance times scale overflows a float");
  return env;
}

EnvironmentDesc parseEnvironmentKey(const std::string& sceneFile, const json& value,
                                    std::vector<std::string>& warnings) {
  const std::string prefix = "environment";
  if (!value.is_object())
    throwInputError(sceneFile, prefix, std::string("expected an object, got ") + value.type_name());
  EnvironmentDesc env;
  env.enabled = true;
  for (auto it = value.begin(); it != value.end(); ++it)
    if (it.key() != "radiance" && it.key() != "file" && it.key() != "scale" && it.key() != "rotate_y")
      warnings.push_back(sceneFile + ": " + prefix + "." + it.key() + ": unknown key, ignored");
  if (value.find("radiance") == value.end() && value.find("file") == value.end())
    throwInputError(sceneFile, prefix, "needs \"radiance\" or \"file\"");
  if (auto it = value.find("radiance"); it != value.end()) {
    const std::string where = prefix + ".radiance";
    if (!it->is_array() || it->size() != 3) throwInputError(sceneFile, where, "expected an array of 3 numbers");
    for (int c = 0; c < 3; ++c) {
      env.radiance[c] = number(sceneFile, (*it)[c], where + "[" + std::to_string(c) + "]");
      if (env.radiance[c] < 0.0f) throwInputError(sceneFile, where, "components must be >= 0");
    }
  }
  if (auto it = value.find("scale"); it != value.end()) {
    env.scale = number(sceneFile, *it, prefix + ".scale");
    if (env.scale < 0.0f) throwInputError(sceneFile, prefix + ".scale", "must be >= 0");
  }
  if (auto it = value.find("rotate_y"); it != value.end()) env.rotateYDegrees = number(sceneFile, *it, prefix + ".rotate_y");
  if (auto it = value.find("file"); it != value.end()) {
    const std::string where = prefix + ".file";
    if (!it->is_string() || it->get<std::string>().empty())
      throwInputError(sceneFile, where, "expected a file name");
    const std::filesystem::path folder = std::filesystem::path(sceneFile).parent_path();
    env.file = (folder / it->get<std::string>()).lexically_normal().string();
    checkMapFile(env.file, sceneFile, where);
  }
  const glm::vec3 total = env.radiance * env.scale;
  if (!(std::isfinite(total.x) && std::isfinite(total.y) && std::isfinite(total.z)))
    throwInputError(sceneFile, prefix + ".scale", "radiance times scale overflows a float");
  return env;
}

}  // namespace montecl
