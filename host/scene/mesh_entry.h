// mesh_entry.h: one entry of a scene file's "meshes" list: the file, its per-mesh transform
// ("transform": scale, rotate, translate, or a row-major 4x4 "matrix"; "instances": a list of such
// transforms, one copy of the mesh each) and material overrides
// ("material": {"type": a material kind, ...}, plus the older "emission" / "two_sided_emission" at the entry's top level).
// parseMeshEntry() validates every key (InputError naming the key path); applyMeshEntry()
// transforms the mesh's triangles (normals by the inverse transpose; a mirroring transform swaps
// two corners so faces keep their side) and gives them overridden copies of their materials.
#pragma once
#include <nlohmann/json.hpp>

#include <glm/glm.hpp>
#include <cstddef>
#include <string>
#include <vector>

#include "scene/json_fields.h"
#include "scene/scene.h"

namespace montecl {

// The material fields a scene file sets for one mesh; the others keep the file's values.
struct MaterialOverride {
  bool kind = false, albedo = false, albedoTexture = false, alphaTexture = false, alphaCutoff = false,
       emission = false, twoSided = false, specular = false, specularExponent = false,
       emissionTexture = false, normalTexture = false, normalScale = false, metallicRoughnessTexture = false,
       kindParams = false;  // eta, k, ior, kindAlpha, metallic, roughness, ... (given with the type)
  MaterialDesc value;
  bool any() const {
    return kind || albedo || albedoTexture || alphaTexture || alphaCutoff || emission || twoSided || specular ||
           specularExponent || kindParams || emissionTexture ||
           normalTexture || normalScale || metallicRoughnessTexture;
  }
};

struct MeshEntry {
  std::string path;   // resolved against the scene file's folder
  std::string where;  // "meshes[i].file"
  std::string prefix;  // "meshes[i]"
  MaterialOverride material;
  bool hasTransform = false;
  glm::dmat4 transform{1.0};  // column vectors (glm): p' = transform * p
  // "instances": one copy of the mesh per transform, placed at instance x transform (flattened:
  // every copy is triangles of its own). Empty: the one mesh at transform.
  std::vector<glm::dmat4> instances;
  // Where copy k is placed (k = 0 without instances).
  glm::dmat4 placement(std::size_t k) const {
    if (instances.empty()) return transform;
    return hasTransform ? instances[k] * transform : instances[k];
  }
};

// missing: where textures that cannot be opened are recorded (the override then not given;
// loadScene reports them); nullptr: such a texture is an InputError.
MeshEntry parseMeshEntry(const JsonCtx& ctx, const nlohmann::json& j, const std::string& prefix,
                         std::vector<MissingTexture>* missing = nullptr);

// Applies the entry to triangles [firstTri, end) of scene (transform, then material overrides)
// and places lights [firstLight, end) (a glTF's KHR_lights_punctual) by its transform. With
// instances, a mesh without lights or emitting materials stays one mesh range in object space,
// placed by placement(k) once per instance (Scene::instances: a two-level BVH renders it); else
// the triangles and lights become one copy per instance, in instance order, each placed by
// placement(k), the copies refused up front when they would not fit in memory.
// Triangles that the transform makes degenerate are dropped and counted. Does not update the
// bounds: call recomputeBounds() when all meshes are in.
void applyMeshEntry(const JsonCtx& ctx, Scene& scene, std::size_t firstTri, std::size_t firstLight,
                    const MeshEntry& mesh);

void recomputeBounds(Scene& scene);

}  // namespace montecl
