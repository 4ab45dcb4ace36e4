// pbrt_materials.cpp: pbrt-v4 textures and materials (pbrt_materials.h): reads their parameters,
// writes PbrtTexture / MaterialDesc.
#include "scene/pbrt_materials.h"

#include <algorithm>
#include <cmath>

#include "scene/load_util.h"
#include "scene/value_limits.h"

namespace montecl {
namespace {

std::string whereOf(const PbrtParams& p) { return p.loc.str() + ": "; }

// A colour parameter given as a spectrum or as a named texture: the constant into *value, an
// image into *file (with its sampling). False when absent.
bool colourOrTexture(const PbrtParams& p, const std::string& name, const PbrtTextures& textures, glm::vec3& value,
                     std::string* file, TextureSampling* sampling, std::vector<std::string>& warnings) {
  const std::string tex = p.getTexture(name);
  if (!tex.empty()) {
    auto it = textures.find(tex);
    if (it == textures.end()) pbrtFail(p.find(name)->loc, "texture '" + oneLine(tex, 60) + "' is not defined");
    value = it->second.value;
    if (!it->second.file.empty()) {
      if (file) {
        *file = it->second.file, *sampling = it->second.sampling;
      } else {
        warnings.push_back(p.find(name)->loc.str() + ": '" + name + "': montecl reads an image texture here only as its colour factor; image '" + oneLine(tex, 60) + "' left out");
      }
    }
    return true;
  }
  return pbrtSpectrum(p, name, value, warnings);
}

// A float parameter or a constant float texture (an image texture: warned, its factor used).
double floatOrTexture(const PbrtParams& p, const std::string& name, double fallback, const PbrtTextures& textures,
                      std::vector<std::string>& warnings) {
  const std::string tex = p.getTexture(name);
  if (tex.empty()) return p.getFloat(name, fallback);
  auto it = textures.find(tex);
  if (it == textures.end()) pbrtFail(p.find(name)->loc, "texture '" + oneLine(tex, 60) + "' is not defined");
  if (!it->second.file.empty())
    warnings.push_back(p.find(name)->loc.str() + ": '" + name + "': textured values are not read by montecl here; the texture's factor is used");
  return it->second.value.x;
}

// GGX alpha from pbrt's roughness parameters: uroughness / vroughness (default: roughness), mapped
// by pbrt's RoughnessToAlpha (sqrt) unless remaproughness is false; anisotropy is not read by
// montecl (the geometric mean is used, with a warning).
float alphaOf(const PbrtParams& p, const PbrtTextures& textures, const std::string& prefix, std::vector<std::string>& warnings) {
  const double r = floatOrTexture(p, prefix + "roughness", 0.0, textures, warnings);
  const double u = floatOrTexture(p, prefix + "uroughness", r, textures, warnings);
  const double v = floatOrTexture(p, prefix + "vroughness", r, textures, warnings);
  const bool remap = p.getBool("remaproughness", true);
  if (!(u >= 0.0 && v >= 0.0)) pbrtFail(p.loc, "roughness must be >= 0");
  double au = remap ? std::sqrt(u) : u, av = remap ? std::sqrt(v) : v;
  if (std::abs(au - av) > 1e-6 * std::max(au, av))
    warnings.push_back(whereOf(p) + "anisotropic roughness (u " + std::to_string(u) + ", v " + std::to_string(v) +
                       ") not read by montecl; the isotropic mean sqrt(alpha_u alpha_v) is used");
  double a = std::sqrt(au * av);
  if (a > 1.0) {
    warnings.push_back(whereOf(p) + "GGX alpha " + std::to_string(a) + " above montecl's limit 1, clamped");
    a = 1.0;
  }
  return float(a);
}

void conductor(const PbrtParams& p, const PbrtTextures& textures, const std::string& prefix, MaterialDesc& d,
               std::vector<std::string>& warnings) {
  d.kind = MCL_MATERIAL_conductor;
  glm::vec3 reflectance;
  if (colourOrTexture(p, prefix + "reflectance", textures, reflectance, nullptr, nullptr, warnings)) {
    // pbrt-v4's artist-friendly conductor: eta 1 and k = 2 sqrt(r) / sqrt(1 - r).
    d.eta = glm::vec3(1.0f);
    for (int c = 0; c < 3; ++c) {
      const float r = std::min(std::max(reflectance[c], 0.0f), 0.9999f);
      d.k[c] = 2.0f * std::sqrt(r) / std::sqrt(1.0f - r);
    }
  } else {
    glm::vec3 eta, k;
    if (!colourOrTexture(p, prefix + "eta", textures, eta, nullptr, nullptr, warnings)) eta = glm::vec3(0.201005f, 0.92375f, 1.10222f);  // metal-Cu-eta
    if (!colourOrTexture(p, prefix + "k", textures, k, nullptr, nullptr, warnings)) k = glm::vec3(3.91326f, 2.45305f, 2.14209f);  // metal-Cu-k
    d.eta = eta, d.k = k;
    for (const auto& [key, v] : {std::make_pair("eta", eta), std::make_pair("k", k)})
      if (const std::string bad = magnitudeProblem(glm::dvec3(v), kMaxConductorIndex, kConductorIndexReason); !bad.empty())
        pbrtFail(p.find(prefix + key) ? p.find(prefix + key)->loc : p.loc, "conductor '" + prefix + key + "': " + bad);
  }
  d.kindAlpha = alphaOf(p, textures, prefix, warnings);
  d.roughness = std::sqrt(d.kindAlpha);
}

float etaOf(const PbrtParams& p, const std::string& name, std::vector<std::string>& warnings) {
  glm::vec3 eta(1.5f);
  if (pbrtSpectrum(p, name, eta, warnings) && p.find(name)->type == "spectrum" && p.find(name)->strings.empty() &&
      (eta.x != eta.y || eta.y != eta.z))
    warnings.push_back(p.find(name)->loc.str() + ": '" + name + "': a varying index (dispersion) is not rendered by montecl; its value at 550 nm is used");
  if (!(eta.y > 0.0f && std::isfinite(eta.y))) pbrtFail(p.find(name)->loc, "'" + name + "' must be a finite number > 0");
  return eta.y;
}

// The layer of pbrt-v4's coated materials (coateddiffuse, coatedconductor): thickness, the walk's
// maxdepth and nsamples; a scattering layer (albedo, g) is warned and left out.
void coatLayer(const PbrtParams& p, const PbrtTextures& textures, const std::string& type, MaterialDesc& d,
               std::vector<std::string>& warnings) {
  const double thickness = floatOrTexture(p, "thickness", 0.01, textures, warnings);
  if (!(thickness >= 0.0) || !std::isfinite(thickness)) pbrtFail(p.loc, type + ": 'thickness' must be >= 0");
  d.thickness = float(std::max(thickness, 1e-6));  // pbrt keeps it above a small epsilon too
  const int maxDepth = p.getInt("maxdepth", 10), samples = p.getInt("nsamples", 1);
  if (maxDepth < 1 || maxDepth > 1000) pbrtFail(p.loc, type + ": 'maxdepth' must be in [1, 1000]");
  if (samples < 1 || samples > 64) pbrtFail(p.loc, type + ": 'nsamples' must be in [1, 64]");
  d.layerMaxDepth = maxDepth, d.layerSamples = samples;
  glm::vec3 coatAlbedo(0.0f);
  if (colourOrTexture(p, "albedo", textures, coatAlbedo, nullptr, nullptr, warnings) && coatAlbedo != glm::vec3(0.0f))
    warnings.push_back(whereOf(p) + "Material \"" + type + "\": a scattering layer ('albedo', 'g') is not read by montecl; a clear layer is used");
  p.ignore("g");
}

// pbrt-v4's coateddiffuse: montecl's coated_diffuse, the same layered model (a dielectric coat of
// index eta and GGX roughness over a Lambertian base, a layer of some thickness, a random walk of
// at most maxdepth events, nsamples walks).
void coatedDiffuse(const PbrtParams& p, const PbrtTextures& textures, MaterialDesc& d, std::vector<std::string>& warnings) {
  d.kind = MCL_MATERIAL_coated_diffuse;
  d.albedo = glm::vec3(0.5f);
  colourOrTexture(p, "reflectance", textures, d.albedo, &d.albedoTexture, &d.albedoSampling, warnings);
  d.kindAlpha = alphaOf(p, textures, "", warnings);
  d.ior = etaOf(p, "eta", warnings);
  coatLayer(p, textures, "coateddiffuse", d, warnings);
}

// pbrt-v4's coatedconductor: montecl's coated_conductor: the conductor.* parameters as pbrt's
// conductor (the metal's own eta, k or reflectance; the BSDF divides them by the coat's index, as
// pbrt-v4 does), the interface.* ones as the coat (index, GGX roughness), the same layer.
void coatedConductor(const PbrtParams& p, const PbrtTextures& textures, MaterialDesc& d,
                     std::vector<std::string>& warnings) {
  conductor(p, textures, "conductor.", d, warnings);
  d.kind = MCL_MATERIAL_coated_conductor;
  d.baseAlpha = d.kindAlpha;
  d.kindAlpha = alphaOf(p, textures, "interface.", warnings);
  d.ior = etaOf(p, "interface.eta", warnings);
  coatLayer(p, textures, "coatedconductor", d, warnings);
}

}  // namespace

PbrtTexture pbrtTexture(const std::string& klass, const PbrtParams& p, const PbrtTextures& known,
                        const std::string& baseFile, std::vector<std::string>& warnings) {
  PbrtTexture t;
  auto colour = [&](const std::string& name, glm::vec3 fallback) -> PbrtTexture {
    PbrtTexture c;
    c.value = fallback;
    const std::string tex = p.getTexture(name);
    if (!tex.empty()) {
      auto it = known.find(tex);
      if (it == known.end()) pbrtFail(p.find(name)->loc, "texture '" + oneLine(tex, 60) + "' is not defined");
      return it->second;
    }
    pbrtSpectrum(p, name, c.value, warnings);
    return c;
  };
  if (klass == "imagemap") {
    const std::string name = p.getString("filename", "");
    if (name.empty()) pbrtFail(p.loc, "imagemap: 'string filename' is required");
    t.file = besideFile(baseFile, name);
    t.value = glm::vec3(float(p.getFloat("scale", 1.0)));
    if (p.getBool("invert", false)) warnings.push_back(whereOf(p) + "imagemap: 'invert' not read by montecl, ignored");
    const std::string mapping = p.getString("mapping", "uv");
    if (mapping != "uv") warnings.push_back(whereOf(p) + "imagemap: mapping '" + mapping + "' not read by montecl; uv used");
    // pbrt's uv mapping: s = su u + du, t = sv v + dv.
    const float su = float(p.getFloat("uscale", 1.0)), sv = float(p.getFloat("vscale", 1.0));
    const float du = float(p.getFloat("udelta", 0.0)), dv = float(p.getFloat("vdelta", 0.0));
    t.sampling.row0 = glm::vec3(su, 0.0f, du);
    t.sampling.row1 = glm::vec3(0.0f, sv, dv);
    const std::string wrap = p.getString("wrap", "repeat");
    const std::uint32_t w = wrap == "clamp" ? 1u : 0u;
    if (wrap != "repeat" && wrap != "clamp") warnings.push_back(whereOf(p) + "imagemap: wrap '" + wrap + "' not read by montecl; repeat used");
    t.sampling.wrapS = t.sampling.wrapT = w;
    for (const char* quiet : {"filter", "maxanisotropy"}) p.ignore(quiet);  // montecl filters with its own footprints
    const std::string encoding = p.getString("encoding", "sRGB");
    if (encoding != "sRGB")
      warnings.push_back(whereOf(p) + "imagemap: encoding '" + oneLine(encoding, 40) +
                         "' not read by montecl; it decodes 8-bit images as sRGB and float ones as linear");
    return t;
  }
  if (klass == "constant") return colour("value", glm::vec3(1.0f));
  if (klass == "scale") {
    PbrtTexture a = colour("tex", glm::vec3(1.0f)), b = colour("scale", glm::vec3(1.0f));
    if (!a.file.empty() && !b.file.empty()) {
      warnings.push_back(whereOf(p) + "scale: the product of two images is not read by montecl; the first image is used");
      b.file.clear(), b.value = glm::vec3(1.0f);
    }
    PbrtTexture out = a.file.empty() ? b : a;
    out.value = a.value * b.value;
    out.exact = a.exact && b.exact;
    return out;
  }
  if (klass == "checkerboard" || klass == "mix" || klass == "directionmix") {
    const bool checker = klass == "checkerboard";
    PbrtTexture a = colour(checker ? "tex1" : "tex1", glm::vec3(1.0f)), b = colour(checker ? "tex2" : "tex2", glm::vec3(0.0f));
    float amount = 0.5f;
    if (klass == "mix") amount = float(p.getFloat("amount", 0.5));
    for (const char* quiet : {"dimension", "uscale", "vscale", "udelta", "vdelta", "mapping", "dir"}) p.ignore(quiet);
    warnings.push_back(whereOf(p) + "Texture \"" + klass + "\" is not rendered by montecl; its mean colour is used");
    PbrtTexture out;
    out.value = a.value * (1.0f - amount) + b.value * amount;
    out.exact = false;
    return out;
  }
  warnings.push_back(whereOf(p) + "Texture \"" + oneLine(klass, 40) + "\" not read by montecl; white used");
  for (const PbrtParam& q : p.list) q.used = true;
  t.exact = false;
  return t;
}

MaterialDesc pbrtMaterial(const std::string& type, const PbrtParams& p, const PbrtTextures& textures,
                          const std::map<std::string, MaterialDesc>& named, const std::string& baseFile,
                          std::vector<std::string>& warnings) {
  MaterialDesc d;
  d.kind = MCL_MATERIAL_diffuse;
  d.albedo = glm::vec3(0.5f);
  auto diffuse = [&](const std::string& param, glm::vec3 fallback) {
    d.kind = MCL_MATERIAL_diffuse;
    d.albedo = fallback;
    colourOrTexture(p, param, textures, d.albedo, &d.albedoTexture, &d.albedoSampling, warnings);
  };
  if (type == "diffuse") {
    diffuse("reflectance", glm::vec3(0.5f));
  } else if (type == "conductor") {
    conductor(p, textures, "", d, warnings);
  } else if (type == "dielectric" || type == "thindielectric") {
    d.kind = type == "dielectric" ? MCL_MATERIAL_dielectric : MCL_MATERIAL_thin_dielectric;
    d.ior = etaOf(p, "eta", warnings);
    if (type == "dielectric") {
      d.kindAlpha = alphaOf(p, textures, "", warnings);
    }
  } else if (type == "coateddiffuse") {
    coatedDiffuse(p, textures, d, warnings);
  } else if (type == "coatedconductor") {
    coatedConductor(p, textures, d, warnings);
  } else if (type == "diffusetransmission") {
    diffuse("reflectance", glm::vec3(0.25f));
    p.ignore("transmittance");
    warnings.push_back(whereOf(p) + "Material \"diffusetransmission\": montecl renders its reflection only (diffuse)");
  } else if (type == "mix") {
    const PbrtParam* m = p.find("materials");
    if (!m || m->type != "string" || m->strings.empty()) pbrtFail(p.loc, "mix: 'string materials' [ \"a\" \"b\" ] is required");
    p.ignore("amount");
    auto it = named.find(m->strings[0]);
    if (it == named.end()) pbrtFail(m->loc, "mix: material '" + oneLine(m->strings[0], 60) + "' is not defined");
    warnings.push_back(whereOf(p) + "Material \"mix\": montecl does not mix materials; the first, '" + oneLine(m->strings[0], 60) + "', is used");
    d = it->second;
  } else if (type == "interface" || type == "none" || type == "") {
    // No surface (a medium's boundary): a sheet of index 1 lets light through unchanged.
    d.kind = MCL_MATERIAL_thin_dielectric;
    d.ior = 1.0f;
  } else {
    warnings.push_back(whereOf(p) + "Material \"" + oneLine(type, 40) + "\" not read by montecl; rendered as diffuse grey 0.5");
    for (const PbrtParam& q : p.list) q.used = true;
  }
  if (const std::string nm = p.getString("normalmap", ""); !nm.empty()) d.normalTexture = besideFile(baseFile, nm);
  return d;
}

void notePbrtTextureFile(Scene& scene, PbrtTexture& t, const PbrtParams& p) {
  if (!fileProblem(t.file).empty()) {
    MissingTexture m;
    const PbrtLoc& at = p.find("filename")->loc;
    m.file = at.file;
    m.where = "line " + std::to_string(at.line);
    m.lead = "imagemap '" + oneLine(t.file, 120) + "' cannot be opened";
    m.brief = oneLine(t.file, 120);
    noteMissingTexture(scene.missingTextures, m);
    t.file.clear();
    return;
  }
  scene.inputFiles.push_back(t.file);
}


}  // namespace montecl
