// mitsuba_bsdfs.cpp: Mitsuba BSDFs as montecl material kinds (mitsuba_bsdfs.h).
#include "scene/mitsuba_bsdfs.h"

#include <cmath>

#include "scene/load_util.h"
#include "scene/material_params.h"

namespace montecl {
namespace {

// Wrappers nest; deeper than this is a cycle through <ref>s.
constexpr int kMaxBsdfDepth = 16;

struct NamedIor {
  const char* name;
  double ior;
};
// Refractive indices of common media at visible wavelengths (the names Mitsuba accepts).
constexpr NamedIor kIors[] = {
    {"vacuum", 1.0},          {"helium", 1.00004},      {"hydrogen", 1.00013},   {"air", 1.00028},
    {"carbon dioxide", 1.00045}, {"water", 1.333},      {"acetone", 1.36},       {"ethanol", 1.361},
    {"carbon tetrachloride", 1.461}, {"glycerol", 1.4729}, {"benzene", 1.501},   {"silicone oil", 1.52045},
    {"bromine", 1.661},       {"water ice", 1.31},      {"fused quartz", 1.458}, {"pyrex", 1.47},
    {"acrylic glass", 1.49},  {"polypropylene", 1.49},  {"bk7", 1.5046},         {"sodium chloride", 1.544},
    {"amber", 1.55},          {"pet", 1.575},           {"diamond", 2.419},
};

// An index given as a number or a name (<float> or <string>); fallback when absent.
double iorOf(const MiProps& p, const std::string& name, double fallback) {
  const MiElem e = p.find(name);
  if (!e) return fallback;
  double ior = 0.0;
  if (e.tag() == "string") {
    const std::string s = p.getString(name, "");
    if (!miNamedIor(s, ior)) mitsubaFail(p.doc.loc(e), "'" + name + "': '" + oneLine(s, 40) + "' is not a known material (a number, or bk7, water, air, ...)");
  } else {
    ior = p.getFloat(name, fallback);
  }
  if (!(ior >= 1.0 && ior < 10.0)) mitsubaFail(p.doc.loc(e), "'" + name + "' must be in [1, 10)");
  return ior;
}

// The alpha of a rough BSDF (alpha, or alpha_u / alpha_v: their geometric mean, warned), for GGX;
// *beckmann (the conductor, which has both distributions) is set for Mitsuba's "beckmann" (its
// default), else that distribution is read as GGX of the same alpha with a warning.
float roughness(MiContext& c, const MiProps& p, bool* beckmann = nullptr) {
  const std::string dist = p.getString("distribution", "beckmann");
  if (beckmann && (dist == "beckmann" || dist == "ggx")) *beckmann = dist == "beckmann";
  else if (dist != "ggx")
    c.warn(p.locOf("distribution"), p.type + ": montecl's rough surfaces here are GGX; the " + oneLine(dist, 20) + " distribution is read as GGX of the same alpha");
  p.find("sample_visible");
  double a = 0.1;  // Mitsuba's default
  if (p.find("alpha_u") || p.find("alpha_v")) {
    const double u = p.getFloat("alpha_u", 0.1), v = p.getFloat("alpha_v", 0.1);
    if (u != v) c.warn(p.locOf("alpha_u"), p.type + ": anisotropic roughness is not read by montecl; sqrt(alpha_u alpha_v) is used");
    a = std::sqrt(u * v);
  } else {
    const MiElem e = p.find("alpha");
    if (e && e.tag() == "texture") c.warn(c.doc.loc(e), p.type + ": a roughness texture is not read by montecl; alpha 0.1 is used");
    else a = p.getFloat("alpha", 0.1);
  }
  if (!(a >= 0.0 && a <= 1.0)) mitsubaFail(p.locOf("alpha"), p.type + ": alpha must be in [0, 1]");
  return float(a);
}

void warnScaled(MiContext& c, const MiProps& p, const char* name) {
  glm::vec3 v(1.0f);
  if (miColourInto(c, p, name, &v, nullptr, nullptr) && v != glm::vec3(1.0f))
    c.warn(p.locOf(name), p.type + ": '" + std::string(name) + "' other than 1 is not read by montecl; 1 is used");
}

void dielectric(MiContext& c, const MiProps& p, MaterialDesc& d) {
  const double in = iorOf(p, "int_ior", 1.5046), out = iorOf(p, "ext_ior", 1.00028);
  d.kind = p.type == "thindielectric" ? MCL_MATERIAL_thin_dielectric : MCL_MATERIAL_dielectric;
  d.ior = float(in / out);
  if (p.type == "roughdielectric") d.kindAlpha = roughness(c, p);
  warnScaled(c, p, "specular_reflectance");
  warnScaled(c, p, "specular_transmittance");
}

void conductor(MiContext& c, const MiProps& p, MaterialDesc& d) {
  d.kind = MCL_MATERIAL_conductor;
  d.eta = glm::vec3(0.0f), d.k = glm::vec3(1.0f);  // material "none": a perfect mirror
  const std::string metal = p.getString("material", "none");
  if (metal != "none" && !metalEtaK(metal, d.eta, d.k))
    c.warn(p.locOf("material"), p.type + ": material '" + oneLine(metal, 40) + "' not among montecl's metals (Au, Ag, Cu, Al, Cr); a perfect mirror is used");
  miColourInto(c, p, "eta", &d.eta, nullptr, nullptr);
  miColourInto(c, p, "k", &d.k, nullptr, nullptr);
  if (p.type == "roughconductor") d.kindAlpha = roughness(c, p, &d.beckmann);
  if (miColourInto(c, p, "specular_reflectance", &d.conductorFactor, nullptr, nullptr)) {
    const glm::vec3 f = d.conductorFactor;
    if (!(f.x >= 0.0f && f.y >= 0.0f && f.z >= 0.0f && std::isfinite(f.x + f.y + f.z)))
      mitsubaFail(p.locOf("specular_reflectance"), p.type + ": 'specular_reflectance' must be finite and >= 0");
  }
}

// plastic / roughplastic: a dielectric coat over a diffuse base, as montecl's metal_rough with
// metallic 0 (Lambert under a GGX lobe weighted by Schlick's Fresnel, F0 0.04: an index of 1.5).
void plastic(MiContext& c, const MiProps& p, MaterialDesc& d) {
  d.kind = MCL_MATERIAL_metal_rough;
  d.metallic = 0.0f;
  d.albedo = glm::vec3(0.5f);
  miColourInto(c, p, "diffuse_reflectance", &d.albedo, &d.albedoTexture, &d.albedoSampling);
  d.roughness = p.type == "roughplastic" ? std::sqrt(roughness(c, p)) : 0.0f;  // metal_rough squares it
  iorOf(p, "int_ior", 1.49);
  iorOf(p, "ext_ior", 1.00028);
  p.find("nonlinear");
  warnScaled(c, p, "specular_reflectance");
  c.warn(p.loc, p.type + ": approximated by montecl's metal_rough (metallic 0): a GGX lobe with Schlick's Fresnel at index 1.5 over Lambert; no light bouncing inside the coat, int_ior and nonlinear not read");
}

MiMaterial bsdf(MiContext& c, const MiElem& e, int depth);

// The one nested BSDF of a wrapper (twosided, mask, bumpmap): twosided may hold two, the front
// one is used.
MiMaterial nested(MiContext& c, const MiProps& p, int depth) {
  const std::vector<MiElem> inner = p.objects("bsdf");
  if (inner.empty()) mitsubaFail(p.loc, p.type + ": a nested <bsdf> is required");
  if (inner.size() > 1) c.warn(c.doc.loc(inner[1]), p.type + ": montecl gives both sides one BSDF; the first is used");
  return bsdf(c, inner[0], depth + 1);
}

void mask(MiContext& c, const MiProps& p, MiMaterial& m) {
  glm::vec3 opacity(0.5f);  // Mitsuba's default
  std::string file;
  TextureSampling s;
  miColourInto(c, p, "opacity", &opacity, &file, &s);
  if (!file.empty()) {
    // Mitsuba blends by opacity at random; montecl keeps a hit where it is >= 0.5.
    m.desc.alphaTexture = file;
    m.desc.alphaSampling = s;
    m.desc.alphaCutoff = 0.5f;
    return;
  }
  const float o = (opacity.x + opacity.y + opacity.z) / 3.0f;
  if (o > 0.0f && o < 1.0f)
    c.warn(p.locOf("opacity"), "mask: a constant opacity between 0 and 1 is not blended by montecl; the shape is " +
                                   std::string(o >= 0.5f ? "opaque" : "left out") + " (montecl's cut-outs keep alpha >= 0.5)");
  m.invisible = o < 0.5f;
}

MiMaterial bsdf(MiContext& c, const MiElem& e, int depth) {
  if (depth > kMaxBsdfDepth) mitsubaFail(c.doc.loc(e), "BSDFs nested more than 16 deep (does a <ref> refer to itself?)");
  const MiProps p(c.doc, e);
  MiMaterial m;
  MaterialDesc& d = m.desc;
  const std::string id = c.doc.attr(e, "id");
  const std::string what = "bsdf \"" + oneLine(p.type, 40) + "\"";
  if (p.type == "twosided") {
    m = nested(c, p, depth);
    m.twoSided = true;
  } else if (p.type == "mask") {
    m = nested(c, p, depth);
    mask(c, p, m);
  } else if (p.type == "bumpmap") {
    m = nested(c, p, depth);
    const std::vector<MiElem> tex = p.objects("texture");
    if (tex.empty()) mitsubaFail(p.loc, "bumpmap: a nested height <texture> is required");
    const MiTexture t = miTexture(c, tex[0], "bump");
    m.desc.bumpTexture = t.file;
    m.desc.bumpSampling = t.sampling;
    m.desc.bumpScale = float(p.getFloat("scale", 1.0));
  } else if (p.type == "normalmap") {
    m = nested(c, p, depth);
    const std::optional<MiColour> n = p.getColour("normalmap", c.warnings);
    if (!n || !n->texture) mitsubaFail(p.loc, "normalmap: a 'normalmap' bitmap texture is required");
    const MiTexture t = miTexture(c, n->texture, "bump");
    m.desc.normalTexture = t.file;
    m.desc.normalSampling = t.sampling;
  } else if (p.type == "diffuse") {
    d.kind = MCL_MATERIAL_diffuse;
    d.albedo = glm::vec3(0.5f);
    miColourInto(c, p, "reflectance", &d.albedo, &d.albedoTexture, &d.albedoSampling);
  } else if (p.type == "dielectric" || p.type == "roughdielectric" || p.type == "thindielectric") {
    dielectric(c, p, d);
  } else if (p.type == "conductor" || p.type == "roughconductor") {
    conductor(c, p, d);
  } else if (p.type == "plastic" || p.type == "roughplastic") {
    plastic(c, p, d);
  } else if (p.type == "blendbsdf") {
    m = nested(c, p, depth);
    p.find("weight");
    c.warn(p.loc, "blendbsdf: montecl does not blend BSDFs; the first nested one is used");
  } else {
    c.warn(p.loc, what + " not read by montecl (see docs/mitsuba-format.md); grey diffuse 0.5 is used");
    d.albedo = glm::vec3(0.5f);
    m.desc.name = id.empty() ? p.type : id;
    return m;
  }
  if (m.desc.name.empty()) m.desc.name = id.empty() ? p.type : id;
  p.reportUnused(what, c.warnings);
  return m;
}

}  // namespace

bool miNamedIor(const std::string& name, double& ior) {
  for (const NamedIor& n : kIors)
    if (name == n.name) {
      ior = n.ior;
      return true;
    }
  return false;
}

MiMaterial miBsdf(MiContext& c, const MiElem& e) { return bsdf(c, e, 0); }

}  // namespace montecl
