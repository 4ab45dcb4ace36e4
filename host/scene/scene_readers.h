// scene_readers.h: the one table of the files `montecl render` reads (extension -> reader), from
// which loadScene's dispatch and the message for any other file ("x.stl: montecl reads ...") come.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace montecl {

enum class SceneReader { Json, Mesh, Pbrt, Mitsuba, None };

struct SceneReaderRow {
  const char* extension;  // lower case, with the dot
  SceneReader reader;
};

// The rows, in the order the message lists them; count in *n.
const SceneReaderRow* sceneReaderRows(std::size_t* n);

// The reader of a path by its extension (any case); None when no row names it.
SceneReader sceneReaderOf(const std::string& path);

// ".json, .obj, .ply, .gltf, .glb, .pbrt, .xml": every row's extension, in table order.
std::string readableExtensions();

// What a scene-file reader (pbrt, Mitsuba) does with the textures it could not open: `missing`
// (the command line's) replaces the file's rule; error throws one line listing them all, warn
// appends one warning listing them all (each material renders without its texture).
void settleMissingTextures(Scene& scene, std::optional<MissingTextures> missing, std::vector<std::string>& warnings);

}  // namespace montecl
