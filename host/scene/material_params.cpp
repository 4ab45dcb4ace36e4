// material_params.cpp: the material kinds' scene-file keys (see material_params.h): reads a
// material object's eta / k / metal / alpha / roughness / ior / metallic / clearcoat / sheen, writes
// MaterialDesc.
#include "scene/material_params.h"

#include <cmath>

#include "scene/value_limits.h"

namespace montecl {
namespace {

using nlohmann::json;

// RGB complex indices of refraction of the named metals: the values Mitsuba 3 itself uses for its
// conductor's "material" names in an RGB variant (its tabulated spectra, the pbrt-v3 / PBRT
// measured data, reduced to linear sRGB by Mitsuba's spectrum-to-RGB upsampling when the scene
// is loaded; read back with mi.traverse(mi.load_dict({"type": "conductor", "material": name}))
// under scalar_rgb, Mitsuba 3.x). So a montecl metal matches Mitsuba's in RGB renders.
struct Metal {
  const char* name;
  float eta[3], k[3];
};
const Metal kMetals[] = {
    {"Au", {0.143036f, 0.375307f, 1.44205f}, {3.983f, 2.38556f, 1.60336f}},
    {"Ag", {0.155276f, 0.116728f, 0.138388f}, {4.82835f, 3.12222f, 2.1469f}},
    {"Cu", {0.201005f, 0.92375f, 1.10222f}, {3.91326f, 2.45305f, 2.14209f}},
    {"Al", {1.6575f, 0.880405f, 0.521244f}, {9.22381f, 6.2695f, 4.837f}},
    {"Cr", {4.36967f, 2.91651f, 1.6549f}, {5.20655f, 4.23131f, 3.7547f}},
};

float unitKey(const JsonCtx& ctx, const json& v, const std::string& where) {
  const float f = getFloat(ctx, v, where);
  if (!(f >= 0.0f && f <= 1.0f)) jsonFail(ctx, where, "must be in [0, 1]");
  return f;
}

glm::vec3 finiteColor(const JsonCtx& ctx, const json& v, const std::string& where) {
  const glm::vec3 c = getColor(ctx, v, where);
  if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z))) jsonFail(ctx, where, "must be finite");
  return c;
}

// A conductor's eta or k: finite and within what its Fresnel terms can square in float.
glm::vec3 conductorIndex(const JsonCtx& ctx, const json& v, const std::string& where) {
  const glm::vec3 c = finiteColor(ctx, v, where);
  if (const std::string p = magnitudeProblem(glm::dvec3(c), kMaxConductorIndex, kConductorIndexReason); !p.empty())
    jsonFail(ctx, where, p);
  return c;
}

}  // namespace

bool metalEtaK(const std::string& name, glm::vec3& eta, glm::vec3& k) {
  for (const Metal& m : kMetals)
    if (name == m.name) {
      eta = glm::vec3(m.eta[0], m.eta[1], m.eta[2]);
      k = glm::vec3(m.k[0], m.k[1], m.k[2]);
      return true;
    }
  return false;
}

bool parseKindParams(const JsonCtx& ctx, const json& j, const std::string& prefix, MaterialDesc& d) {
  bool any = false;
  const json* metal = optionalKey(j, "metal");
  if (metal) {
    any = true;
    for (const char* key : {"eta", "k"})
      if (optionalKey(j, key)) jsonFail(ctx, childKey(prefix, key), "give either \"metal\" or eta/k, not both");
    const std::string name = getString(ctx, *metal, prefix + ".metal", "a metal name");
    if (!metalEtaK(name, d.eta, d.k)) jsonFail(ctx, prefix + ".metal", "unknown metal '" + name + "' (known: Au, Ag, Cu, Al, Cr)");
  }
  if (const json* v = optionalKey(j, "eta")) any = true, d.eta = conductorIndex(ctx, *v, prefix + ".eta");
  if (const json* v = optionalKey(j, "k")) any = true, d.k = conductorIndex(ctx, *v, prefix + ".k");
  if (const json* v = optionalKey(j, "ior")) {
    any = true;
    d.ior = getFloat(ctx, *v, prefix + ".ior");
    if (!(d.ior > 0.0f && std::isfinite(d.ior))) jsonFail(ctx, prefix + ".ior", "must be a finite number > 0");
  }
  const json* alpha = optionalKey(j, "alpha");
  const json* rough = optionalKey(j, "roughness");
  if (alpha && rough) jsonFail(ctx, prefix + ".roughness", "give either \"alpha\" or \"roughness\" (alpha = roughness^2), not both");
  // "roughness" is glTF's perceptual roughness: the conductor's alpha is its square; metal_rough
  // keeps it as the glTF factor (and squares it itself).
  if (alpha) {
    any = true;
    d.kindAlpha = unitKey(ctx, *alpha, prefix + ".alpha");
    d.roughness = std::sqrt(d.kindAlpha);
  }
  if (rough) {
    any = true;
    d.roughness = unitKey(ctx, *rough, prefix + ".roughness");
    d.kindAlpha = d.roughness * d.roughness;
  }
  if (const json* v = optionalKey(j, "metallic")) any = true, d.metallic = unitKey(ctx, *v, prefix + ".metallic");
  // metal_rough's clearcoat (glTF KHR_materials_clearcoat's factor and perceptual roughness).
  if (const json* v = optionalKey(j, "clearcoat")) any = true, d.clearcoat = unitKey(ctx, *v, prefix + ".clearcoat");
  if (const json* v = optionalKey(j, "clearcoat_roughness"))
    any = true, d.clearcoatRoughness = unitKey(ctx, *v, prefix + ".clearcoat_roughness");
  // metal_rough's sheen (glTF KHR_materials_sheen's colour factor and perceptual roughness).
  if (const json* v = optionalKey(j, "sheen_color")) {
    any = true;
    d.sheenColor = getColor(ctx, *v, prefix + ".sheen_color");
    if (!(d.sheenColor.x <= 1.0f && d.sheenColor.y <= 1.0f && d.sheenColor.z <= 1.0f))
      jsonFail(ctx, prefix + ".sheen_color", "components must be in [0, 1]");
  }
  if (const json* v = optionalKey(j, "sheen_roughness")) any = true, d.sheenRoughness = unitKey(ctx, *v, prefix + ".sheen_roughness");
  // conductor: the microfacets (Mitsuba's and Tungsten's "beckmann", or "ggx") and a factor on F.
  if (const json* v = optionalKey(j, "distribution")) {
    any = true;
    const std::string name = getString(ctx, *v, prefix + ".distribution", "\"ggx\" or \"beckmann\"");
    if (name != "ggx" && name != "beckmann") jsonFail(ctx, prefix + ".distribution", "must be \"ggx\" or \"beckmann\"");
    d.beckmann = name == "beckmann";
  }
  if (const json* v = optionalKey(j, "specular_reflectance"))
    any = true, d.conductorFactor = getColor(ctx, *v, prefix + ".specular_reflectance");
  // coated_diffuse's layer: thickness > 0; the walk's bounce limit and walks per evaluation.
  if (const json* v = optionalKey(j, "thickness")) {
    any = true;
    d.thickness = getFloat(ctx, *v, prefix + ".thickness");
    if (!(d.thickness > 0.0f && std::isfinite(d.thickness))) jsonFail(ctx, prefix + ".thickness", "must be a finite number > 0");
  }
  if (const json* v = optionalKey(j, "base_alpha")) any = true, d.baseAlpha = unitKey(ctx, *v, prefix + ".base_alpha");
  if (const json* v = optionalKey(j, "max_depth"))
    any = true, d.layerMaxDepth = getPositiveInt(ctx, *v, prefix + ".max_depth", 1000, "a positive integer up to 1000");
  if (const json* v = optionalKey(j, "samples"))
    any = true, d.layerSamples = getPositiveInt(ctx, *v, prefix + ".samples", 64, "a positive integer up to 64");
  return any;
}

}  // namespace montecl
