// glossy_material.h: checks of a material's glossy lobe (Ks, Ns) at load, for every loader: Ks in
// [0, 1], Ns finite and >= 0, and energy conservation (Kd + Ks <= 1 per channel, else both are
// scaled down by the same factor, with a warning).
#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"

namespace montecl {

// Throws InputError "<file>: <where>: <problem>" for Ks outside [0, 1] or a bad Ns. Returns the
// factor Kd and Ks were multiplied by (1 when Kd + Ks <= 1 in every channel).
float checkGlossyMaterial(const std::string& file, const std::string& where, MaterialDesc& m);

// Tracks the materials of one file that were scaled, for one warning per file.
struct GlossyScaling {
  std::size_t count = 0;
  std::string first;  // the first material's name
  float firstFactor = 1.0f;
  void note(const std::string& name, float factor);
  // Appends "<file>: material '<first>': Kd + Ks > 1, ... (N more)" when any was scaled.
  void warn(const std::string& file, std::vector<std::string>* warnings) const;
};

}  // namespace montecl
