// scene_digest.h: what a render was made of, as text for its provenance (image/provenance.h): a
// hash of the loaded scene's content.
#pragma once
#include <string>

#include "scene/scene.h"

namespace montecl {

// 16 hex digits: FNV-1a over the triangles (vertices, material index, normals, uvs), the materials
// (kind, albedo, emission, specular lobe, alpha cutoff, two-sided emission and the CONTENT of their
// albedo, alpha and emission textures), the environment (radiance, scale, rotation and its map's content) and
// the camera (position, target, up, field of view, lens) as loaded. Not the image size (compared
// separately), render settings, names or file paths: the same geometry loaded from another folder
// or file name is the same scene; any changed vertex, colour, texel or view is not. The render
// identity of checkpoints (render/checkpoint.h renderKey) is built from it.
std::string sceneDigest(const Scene& scene);

// integratorSettings(), the settings string, comes from the settings table (scene/render_settings.h).

}  // namespace montecl
