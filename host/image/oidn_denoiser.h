// oidn_denoiser.h: Open Image Denoise's "RT" filter on an RGB image with albedo and normal
// guides. The library is dlopened on first use only (a render without --denoise never loads it):
// $MONTECL_OIDN_LIBRARY, else the venv that `scripts/setup.sh --oidn` fills ($MONTECL_OIDN_VENV or
// ~/.cache/montecl/oidn-venv, PyPI's pyoidn wheel). Reads the library; writes nothing.
#pragma once
#include <string>
#include <vector>

namespace montecl {

// The library file montecl would load ("" when no candidate exists).
std::string oidnLibraryPath();
// Loads the library (once per process), resolves its symbols and creates and commits its CPU device.
// Returns "" when it is usable, else one line saying why not and how to install it
// (`bash scripts/setup.sh --oidn`).
std::string oidnProblem();

// Denoises `color` (width * height RGB floats, linear HDR radiance, row 0 at the top) with the
// guides albedo (RGB in [0, 1]) and normal (XYZ in [-1, 1]), both as noisy as the color: each is
// denoised first (OIDN's prefiltering, at its fast quality), then the color with the clean guides
// (cleanAux) in the filter's quality mode `quality` (oidn::kQuality* of image/oidn_api.h).
// Returns the denoised RGB. Throws RuntimeError when the library is missing or reports an error.
std::vector<float> oidnDenoise(int width, int height, const std::vector<float>& color,
                               const std::vector<float>& albedo, const std::vector<float>& normal, int quality);

}  // namespace montecl
