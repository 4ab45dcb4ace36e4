// dark_image.h: whether a rendered image is black or nearly so, and the warning that names its
// likely cause and the option that changes it (a render that exits 0 with a black frame otherwise
// says nothing). Reads the image's linear RGB only.
#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"

namespace montecl {

// "" when the image is not nearly black (its 99th-percentile luminance is 1% of white or more),
// else the warning's text (without "montecl: warning: "). rgb: width x height linear RGB.
std::string darkImageWarning(const std::vector<float>& rgb, const Scene& scene);

}  // namespace montecl
