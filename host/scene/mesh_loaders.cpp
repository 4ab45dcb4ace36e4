// mesh_loaders.cpp: the dispatch on a mesh file's extension (see mesh_loaders.h).
#include "scene/mesh_loaders.h"

#include "scene/load_util.h"
#include "util/errors.h"

namespace montecl {

MeshFormat meshFormatOf(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".obj") return MeshFormat::Obj;
  if (ext == ".ply") return MeshFormat::Ply;
  if (ext == ".gltf" || ext == ".glb") return MeshFormat::Gltf;
  return MeshFormat::Unknown;
}

bool loadMeshFile(const std::string& path, Scene& scene, std::vector<std::string>* warnings, Camera* camera,
                  std::optional<unsigned> sceneIndex) {
  const MeshFormat format = meshFormatOf(path);
  if (sceneIndex && format != MeshFormat::Gltf) throwSceneOptionError(path);
  switch (format) {
    case MeshFormat::Obj: loadObjInto(path, scene, warnings); return false;
    case MeshFormat::Ply: loadPlyInto(path, scene, warnings); return false;
    case MeshFormat::Gltf: return loadGltfInto(path, scene, warnings, camera, sceneIndex);
    case MeshFormat::Unknown: break;
  }
  const std::string ext = lowerExtension(path);
  loadFail(path, "", "unknown mesh format '" + (ext.empty() ? std::string("(no extension)") : ext) +
                         "' (montecl reads .obj, .ply, .gltf and .glb)");
}

void throwSceneOptionError(const std::string& path) {
  throwInputError("--scene", "", oneLine(path) + " is not a glTF file: only a glTF model (.gltf, .glb) holds scenes to choose from");
}

}  // namespace montecl
