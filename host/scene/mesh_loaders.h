// mesh_loaders.h: the mesh file formats montecl reads besides OBJ (scene.h loadObjInto()), and
// the one dispatch on a file's extension used by bare meshes and scene-file "file" entries.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace montecl {

// PLY (ply_mesh.cpp): ASCII or binary; throws InputError "<ply>: <where>: <problem>".
void loadPlyInto(const std::string& path, Scene& scene, std::vector<std::string>* warnings = nullptr);

// glTF 2.0 (gltf_mesh.cpp): .gltf or .glb. Returns whether the file has a perspective camera in
// its scene, which is then stored in *camera (when given). `sceneIndex` picks one of the file's
// scenes[] (gltf_instancing.h gltfSceneIndex: default the file's "scene", else 0).
bool loadGltfInto(const std::string& path, Scene& scene, std::vector<std::string>* warnings = nullptr,
                  Camera* camera = nullptr, std::optional<unsigned> sceneIndex = std::nullopt);

enum class MeshFormat { Obj, Ply, Gltf, Unknown };
MeshFormat meshFormatOf(const std::string& path);  // by extension: .obj, .ply, .gltf/.glb

// Loads a mesh file of any known format (Unknown: InputError naming the extension). Returns
// whether it brought a camera (glTF), stored in *camera. sceneIndex: a glTF file's scene (the
// command line's --scene); given for another format, InputError "--scene: ...".
bool loadMeshFile(const std::string& path, Scene& scene, std::vector<std::string>* warnings, Camera* camera,
                  std::optional<unsigned> sceneIndex = std::nullopt);

// The one message for --scene given with a file that is not a glTF model (InputError).
[[noreturn]] void throwSceneOptionError(const std::string& path);

}  // namespace montecl
