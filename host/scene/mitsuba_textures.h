// mitsuba_textures.h: Mitsuba texture plugins as montecl reads them: a `bitmap` as an image file
// with its UV transform and wrap mode, a `checkerboard` (and any other) as its mean colour with a
// warning. Reads <texture> elements; notes the files in the scene's inputs (or missing textures).
#pragma once
#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "scene/mitsuba_props.h"
#include "scene/scene.h"

namespace montecl {

// What a reader of a Mitsuba file shares: the document, the scene being filled, the warnings.
struct MiContext {
  const MiDocument& doc;
  Scene& scene;
  std::vector<std::string>& warnings;
  void warn(const MiLoc& at, const std::string& text) { warnings.push_back(at.str() + ": " + text); }
};

struct MiTexture {
  std::string file;  // image (resolved path), "" for a constant or a file that cannot be opened
  glm::vec3 value{1.0f};  // the colour where there is no file
  TextureSampling sampling;
};

// `role` names the slot ("reflectance", "opacity", "bump"): a raw bitmap in a colour slot is
// warned about (montecl decodes 8-bit colour textures from sRGB in every colour slot).
MiTexture miTexture(MiContext& c, const MiElem& texture, const std::string& role);

// A colour property as a constant or texture: the constant into *value, the texture's file and
// sampling into *file / *sampling when the slot takes one (else the texture's mean colour, with
// a warning). False when absent.
bool miColourInto(MiContext& c, const MiProps& p, const std::string& name, glm::vec3* value, std::string* file,
                  TextureSampling* sampling);

}  // namespace montecl
