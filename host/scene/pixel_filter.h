// pixel_filter.h: the pixel filter setting (render.filter, --filter, pbrt's PixelFilter, Mitsuba's
// rfilter): its kinds and parameters, their text form ("gaussian,radius=1.5,sigma=0.5"), the
// one-dimensional filter function, and the table the camera stage draws offsets from. Reads and
// writes nothing.
#pragma once
#include <nlohmann/json.hpp>

#include <array>
#include <string>

#include "kernels/shared/types.h"
#include "scene/json_fields.h"

namespace montecl {

enum class FilterType { Box, Triangle, Gaussian, Mitchell, Lanczos };

// Parameters in pixels; each type reads its own (defaults: pbrt-v4's).
struct PixelFilter {
  FilterType type = FilterType::Box;
  float radius = 0.5f;
  float sigma = 0.5f;                      // gaussian: standard deviation
  float b = 1.0f / 3.0f, c = 1.0f / 3.0f;  // mitchell: Mitchell-Netravali B, C
  float tau = 3.0f;                        // lanczos: sinc(x) sinc(x / tau), zero past radius
  bool operator==(const PixelFilter& o) const;
};

// A type's default filter (radius and parameters), false for an unknown name.
bool defaultFilter(const std::string& name, PixelFilter& out);
// "box, triangle, gaussian, mitchell, lanczos"
const char* filterTypeNames();
// The text form: the type, then only the parameters it reads, "type,key=value,...". The default
// box is "box".
std::string filterText(const PixelFilter& f);
// Parses a text form ("gaussian", "gaussian,radius=2"); on bad input returns false and sets
// *problem to one line ("unknown filter 'x' (known: ...)", "radius must be a positive number ...").
bool parseFilterText(const std::string& text, PixelFilter& out, std::string* problem);
// Sets one parameter of f's type by its key ("radius", "sigma", "b", "c", "tau"); on a key f's type
// does not read or a value out of range returns false and sets *problem to one line.
bool setFilterParam(PixelFilter& f, const std::string& key, float value, std::string* problem);
// render.filter in a scene file: a type name or {"type": ..., "radius": ..., ...}; throws one line.
PixelFilter filterFromJson(const JsonCtx& ctx, const nlohmann::json& j, const std::string& where);
// Mitchell and Lanczos have negative lobes, which importance sampling cannot give: clamped to 0.
bool filterHasNegativeLobes(const PixelFilter& f);
// The one-dimensional filter at offset x (pixels) before clamping; the 2D filter is f(x) f(y).
double filterValue(const PixelFilter& f, double x);
// FrameParams::filterKind and filterCdf: the CDF of max(0, f) over [-radius, radius] in
// MCL_FILTER_BINS bins (used by MCL_FILTER_TABLE).
unsigned filterKernelKind(const PixelFilter& f);
std::array<float, MCL_FILTER_BINS> filterCdf(const PixelFilter& f);

}  // namespace montecl
