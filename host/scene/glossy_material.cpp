// glossy_material.cpp: load-time checks of Ks / Ns and the Kd + Ks <= 1 rule (glossy_material.h).
#include "scene/glossy_material.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "util/errors.h"

namespace montecl {

float checkGlossyMaterial(const std::string& file, const std::string& where, MaterialDesc& m) {
  const glm::vec3& ks = m.specular;
  for (int c = 0; c < 3; ++c)
    if (!(ks[c] >= 0.0f && ks[c] <= 1.0f)) {
      char value[96];
      std::snprintf(value, sizeof value, "%g %g %g", double(ks.x), double(ks.y), double(ks.z));
      throwInputError(file, where, std::string("Ks must be in [0, 1], got ") + value);
    }
  if (!(std::isfinite(m.specularExponent) && m.specularExponent >= 0.0f))
    throwInputError(file, where, "Ns must be finite and >= 0, got " + std::to_string(m.specularExponent));
  const glm::vec3 sum = m.albedo + ks;
  const float most = std::max({sum.x, sum.y, sum.z});
  if (!(most > 1.0f) || ks == glm::vec3(0.0f)) return 1.0f;  // Lambert-only albedos are left as given
  const float factor = 1.0f / most;
  m.albedo *= factor;
  m.specular *= factor;
  return factor;
}

void GlossyScaling::note(const std::string& name, float factor) {
  if (factor == 1.0f) return;
  if (count++ == 0) first = name, firstFactor = factor;
}

void GlossyScaling::warn(const std::string& file, std::vector<std::string>* warnings) const {
  if (!warnings || count == 0) return;
  char f[32];
  std::snprintf(f, sizeof f, "%.3g", double(firstFactor));
  warnings->push_back(file + ": material '" + first + "': Kd + Ks > 1, both scaled by " + f +
                      " to conserve energy" +
                      (count > 1 ? " (and " + std::to_string(count - 1) + " more materials)" : std::string()));
}

}  // namespace montecl
