// pixel_filter.cpp: the pixel filter setting's names, text form, scene-file form, filter functions
// and the inverse-CDF table of the camera stage (pixel_filter.h).
#include "scene/pixel_filter.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace montecl {
namespace {

struct FilterTypeInfo {
  const char* name;
  FilterType type;
  float radius;  // pbrt-v4's default radius
};
const FilterTypeInfo kFilterTypes[] = {{"box", FilterType::Box, 0.5f},
                           {"triangle", FilterType::Triangle, 2.0f},
                           {"gaussian", FilterType::Gaussian, 1.5f},
                           {"mitchell", FilterType::Mitchell, 2.0f},
                           {"lanczos", FilterType::Lanczos, 4.0f}};

// Radii above this would let one sample land far outside its pixel for no purpose.
constexpr float kMaxFilterRadius = 16.0f;

const char* filterTypeName(FilterType t) {
  for (const FilterTypeInfo& i : kFilterTypes)
    if (i.type == t) return i.name;
  return "box";
}

// The parameters (besides radius) a type reads, by key.
std::vector<std::pair<const char*, float PixelFilter::*>> filterParamsOf(FilterType t) {
  switch (t) {
    case FilterType::Gaussian: return {{"sigma", &PixelFilter::sigma}};
    case FilterType::Mitchell: return {{"b", &PixelFilter::b}, {"c", &PixelFilter::c}};
    case FilterType::Lanczos: return {{"tau", &PixelFilter::tau}};
    default: return {};
  }
}

std::string filterNumber(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", double(v));
  return buf;
}

// "" when `value` suits parameter `key`, else the rule in words.
std::string filterValueProblem(const std::string& key, float value) {
  if (key == "radius") return std::isfinite(value) && value > 0.0f && value <= kMaxFilterRadius ? "" : "a number in (0, 16]";
  if (key == "b" || key == "c") return std::isfinite(value) ? "" : "a finite number";
  return std::isfinite(value) && value > 0.0f ? "" : "a positive number";
}

}  // namespace

bool setFilterParam(PixelFilter& f, const std::string& key, float value, std::string* problem) {
  const std::string rule = filterValueProblem(key, value);
  if (!rule.empty()) {
    *problem = filterTypeName(f.type) + std::string(" ") + key + " must be " + rule + ", got " + filterNumber(value);
    return false;
  }
  if (key == "radius") {
    f.radius = value;
    return true;
  }
  for (const auto& p : filterParamsOf(f.type))
    if (key == p.first) {
      f.*(p.second) = value;
      return true;
    }
  std::string known = "radius";
  for (const auto& p : filterParamsOf(f.type)) known += std::string(", ") + p.first;
  *problem = std::string("filter ") + filterTypeName(f.type) + " has no parameter '" + key + "' (known: " + known + ")";
  return false;
}

namespace {

double filterSinc(double x) {
  const double px = 3.14159265358979323846 * x;
  return std::fabs(x) < 1e-6 ? 1.0 : std::sin(px) / px;
}

// Mitchell-Netravali's cubic at |x| in [0, 2].
double filterMitchell(double x, double b, double c) {
  x = std::fabs(x);
  if (x < 1.0)
    return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) / 6.0;
  if (x < 2.0)
    return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x + (8 * b + 24 * c)) / 6.0;
  return 0.0;
}

}  // namespace

bool PixelFilter::operator==(const PixelFilter& o) const { return filterText(*this) == filterText(o); }

const char* filterTypeNames() { return "box, triangle, gaussian, mitchell, lanczos"; }

bool defaultFilter(const std::string& name, PixelFilter& out) {
  for (const FilterTypeInfo& i : kFilterTypes)
    if (name == i.name) {
      out = PixelFilter{};
      out.type = i.type;
      out.radius = i.radius;
      return true;
    }
  return false;
}

std::string filterText(const PixelFilter& f) {
  PixelFilter d;
  defaultFilter(filterTypeName(f.type), d);
  std::string s = filterTypeName(f.type);
  if (f.radius != d.radius) s += ",radius=" + filterNumber(f.radius);
  for (const auto& p : filterParamsOf(f.type))
    if (f.*(p.second) != d.*(p.second)) s += std::string(",") + p.first + "=" + filterNumber(f.*(p.second));
  return s;
}

bool parseFilterText(const std::string& text, PixelFilter& out, std::string* problem) {
  std::string name = text.substr(0, text.find(','));
  if (!defaultFilter(name, out)) {
    *problem = "unknown filter '" + name + "' (known: " + filterTypeNames() + ")";
    return false;
  }
  std::size_t at = name.size();
  while (at < text.size()) {
    const std::size_t next = std::min(text.find(',', at + 1), text.size());
    const std::string item = text.substr(at + 1, next - at - 1);
    const std::size_t eq = item.find('=');
    const std::string key = item.substr(0, eq);
    char* end = nullptr;
    const std::string value = eq == std::string::npos ? "" : item.substr(eq + 1);
    const double v = std::strtod(value.c_str(), &end);
    if (eq == std::string::npos || value.empty() || *end != '\0') {
      *problem = "expected key=number after the filter name, got '" + item + "'";
      return false;
    }
    if (!setFilterParam(out, key, float(v), problem)) return false;
    at = next;
  }
  return true;
}

PixelFilter filterFromJson(const JsonCtx& ctx, const nlohmann::json& j, const std::string& where) {
  PixelFilter f;
  std::string problem;
  if (j.is_string()) {
    if (!parseFilterText(j.get<std::string>(), f, &problem) || j.get<std::string>().find(',') != std::string::npos)
      jsonFail(ctx, where, problem.empty() ? "expected a filter name, got " + j.dump() : problem);
    return f;
  }
  if (!j.is_object()) jsonFail(ctx, where, std::string("expected a filter name or object, got ") + j.type_name());
  const nlohmann::json* type = optionalKey(j, "type");
  if (!type || !type->is_string())
    jsonFail(ctx, where + ".type", std::string("expected one of ") + filterTypeNames());
  if (!defaultFilter(type->get<std::string>(), f))
    jsonFail(ctx, where + ".type",
             "unknown filter " + type->dump() + " (known: " + filterTypeNames() + ")");
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it.key() == "type") continue;
    if (!it.value().is_number()) jsonFail(ctx, where + "." + it.key(), "expected a number, got " + it.value().dump());
    if (!setFilterParam(f, it.key(), it.value().get<float>(), &problem)) jsonFail(ctx, where + "." + it.key(), problem);
  }
  return f;
}

bool filterHasNegativeLobes(const PixelFilter& f) {
  return f.type == FilterType::Mitchell || f.type == FilterType::Lanczos;
}

double filterValue(const PixelFilter& f, double x) {
  const double r = f.radius, ax = std::fabs(x);
  if (ax > r) return 0.0;
  switch (f.type) {
    case FilterType::Box: return 1.0;
    case FilterType::Triangle: return r - ax;
    case FilterType::Gaussian: {  // less its value at the radius, so it falls to 0 there (pbrt-v4's)
      const double s2 = double(f.sigma) * f.sigma;
      return std::max(0.0, std::exp(-x * x / (2 * s2)) - std::exp(-r * r / (2 * s2)));
    }
    case FilterType::Mitchell: return filterMitchell(2.0 * x / r, f.b, f.c);
    case FilterType::Lanczos: return filterSinc(x) * filterSinc(x / f.tau);
  }
  return 0.0;
}

unsigned filterKernelKind(const PixelFilter& f) {
  return f.type == FilterType::Box ? MCL_FILTER_BOX : f.type == FilterType::Triangle ? MCL_FILTER_TRIANGLE : MCL_FILTER_TABLE;
}

std::array<float, MCL_FILTER_BINS> filterCdf(const PixelFilter& f) {
  // Each bin's integral of max(0, f) by the midpoint rule on 256 steps (the filters are smooth
  // within a bin, their kinks at bin edges for the default radii).
  constexpr int kSteps = 256;
  const double r = f.radius, w = 2.0 * r / MCL_FILTER_BINS;
  std::array<double, MCL_FILTER_BINS> sum{};
  double total = 0.0;
  for (int i = 0; i < MCL_FILTER_BINS; ++i) {
    double s = 0.0;
    for (int k = 0; k < kSteps; ++k) s += std::max(0.0, filterValue(f, -r + w * (i + (k + 0.5) / kSteps)));
    total += s;
    sum[i] = total;
  }
  std::array<float, MCL_FILTER_BINS> cdf{};
  for (int i = 0; i < MCL_FILTER_BINS; ++i) cdf[i] = total > 0.0 ? float(sum[i] / total) : float(i + 1) / MCL_FILTER_BINS;
  cdf[MCL_FILTER_BINS - 1] = 1.0f;
  return cdf;
}

}  // namespace montecl
