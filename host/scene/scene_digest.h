// scene_digest.h: what a render was made of, as text for its provenance (image/provenance.h): a
// hash of the loaded scene's content and the settings that change what a sample estimates.
#pragma once
#include <string>

#include "scene/scene.h"

namespace montecl {

// 16 hex digits: FNV-1a over the triangles (vertices, material index), the materials (albedo,
// emission) and the camera (position, target, up, field of view) as loaded. Not the image size
// (compared separately), render settings, names or file paths: the same geometry loaded from
// another folder or file name is the same scene; any changed vertex, colour or view is not.
std::string sceneDigest(const Scene& scene);

// The integrator and its settings that change the estimate, e.g. "integrator=ao ao_sampling=cosine
// ao_distance=1 background=0,0,0" or "integrator=direct direct_sampling=mis light_samples=1
// background=0,0,0". Not the seed, sample counts or image size.
std::string integratorSettings(const RenderSettings& render);

}  // namespace montecl
