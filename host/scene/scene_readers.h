// scene_readers.h: the one table of the files `montecl render` reads (extension -> reader), from
// which loadScene's dispatch and the message for any other file ("x.stl: montecl reads ...") come.
#pragma once
#include <cstddef>
#include <string>

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

}  // namespace montecl
