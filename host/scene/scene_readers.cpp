// scene_readers.cpp: the table of files montecl reads and the lookups on it (see scene_readers.h).
#include "scene/scene_readers.h"

#include <cstddef>

#include "scene/load_util.h"
#include "util/errors.h"

namespace montecl {
namespace {

// A new format is one row here (and its loader in loadScene's switch): the message follows.
constexpr SceneReaderRow kRows[] = {
    {".json", SceneReader::Json}, {".obj", SceneReader::Mesh},  {".ply", SceneReader::Mesh},
    {".gltf", SceneReader::Mesh}, {".glb", SceneReader::Mesh},  {".pbrt", SceneReader::Pbrt},
    {".xml", SceneReader::Mitsuba},
};

}  // namespace

const SceneReaderRow* sceneReaderRows(std::size_t* n) {
  *n = sizeof(kRows) / sizeof(kRows[0]);
  return kRows;
}

SceneReader sceneReaderOf(const std::string& path) {
  const std::string ext = lowerExtension(path);
  for (const SceneReaderRow& row : kRows)
    if (ext == row.extension) return row.reader;
  return SceneReader::None;
}

std::string readableExtensions() {
  std::string out;
  for (const SceneReaderRow& row : kRows) out += (out.empty() ? "" : ", ") + std::string(row.extension);
  return out;
}

void settleMissingTextures(Scene& scene, std::optional<MissingTextures> missing, std::vector<std::string>& warnings) {
  if (missing) scene.render.missingTextures = *missing;
  if (scene.missingTextures.empty()) return;
  if (scene.render.missingTextures == MissingTextures::Error) throw InputError(missingTexturesError(scene, 0));
  warnings.push_back(missingTexturesText(scene, 0) + "; rendered without them (each material's factor alone: missing_textures warn)");
}

}  // namespace montecl
