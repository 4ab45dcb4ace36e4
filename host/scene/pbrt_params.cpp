// pbrt_params.cpp: pbrt-v4 parameter lists (pbrt_params.h): reads "type name" [values] from the
// tokenizer, checks the values against the type, serves them by name and reports the unused ones.
#include "scene/pbrt_params.h"

#include <cmath>
#include <cstring>
#include <sstream>

#include "scene/load_util.h"
#include "scene/material_params.h"

namespace montecl {
namespace {

bool numericType(const std::string& t) {
  for (const char* n : {"integer", "float", "point2", "vector2", "point3", "vector3", "normal", "normal3", "point",
                        "vector", "rgb", "color", "blackbody"})
    if (t == n) return true;
  return false;
}
int groupOf(const std::string& t) {
  if (t == "point2" || t == "vector2") return 2;
  if (t == "point3" || t == "vector3" || t == "normal" || t == "normal3" || t == "point" || t == "vector" ||
      t == "rgb" || t == "color")
    return 3;
  return 1;
}

std::string quoted(const PbrtParam& p) { return "'" + p.type + " " + p.name + "'"; }

// Index of refraction at about 550 nm of pbrt-v4's named glasses (Schott's catalogue data,
// which pbrt's spectra tabulate).
struct Glass {
  const char* name;
  float ior;
};
const Glass kGlasses[] = {{"glass-BK7", 1.5185f},  {"glass-BAF10", 1.6700f}, {"glass-FK51A", 1.4866f},
                          {"glass-LASF9", 1.8503f}, {"glass-F5", 1.6034f},   {"glass-F10", 1.6228f},
                          {"glass-F11", 1.6212f}};

}  // namespace

PbrtParams readPbrtParams(PbrtTokenizer& tok, const PbrtLoc& directive) {
  PbrtParams out;
  out.loc = directive;
  while (tok.peek().kind == PbrtToken::String) {
    PbrtToken decl = tok.next();
    PbrtParam p;
    p.loc = decl.loc;
    std::istringstream words(decl.text);
    std::string extra;
    if (!(words >> p.type >> p.name) || (words >> extra))
      pbrtFail(decl.loc, "expected a parameter \"type name\", got \"" + oneLine(decl.text, 60) + "\"");
    const bool numeric = numericType(p.type), isBool = p.type == "bool";
    const bool isString = p.type == "string" || p.type == "texture", spectrum = p.type == "spectrum";
    if (!numeric && !isBool && !isString && !spectrum)
      pbrtFail(decl.loc, "unknown parameter type '" + oneLine(p.type, 40) +
                             "' (pbrt-v4's: integer, float, point2, vector2, point3, vector3, normal, rgb, "
                             "blackbody, spectrum, bool, string, texture)");
    for (const PbrtParam& q : out.list)
      if (q.name == p.name) pbrtFail(decl.loc, "parameter '" + oneLine(p.name, 40) + "' given twice");
    const bool bracket = tok.peek().kind == PbrtToken::Open;
    if (bracket) tok.next();
    for (;;) {
      const PbrtToken& v = tok.peek();
      if (bracket && v.kind == PbrtToken::Close) {
        tok.next();
        break;
      }
      if (!bracket && (p.numbers.size() + p.strings.size() + p.bools.size()) == 1) break;
      if (v.kind == PbrtToken::End)
        pbrtFail(p.loc, "end of file inside the values of " + quoted(p) + (bracket ? " (a ']' is missing)" : ""));
      PbrtToken value = tok.next();
      if (value.kind == PbrtToken::Number && (numeric || spectrum)) {
        if (p.type == "integer" && value.number != std::floor(value.number))
          pbrtFail(value.loc, quoted(p) + ": '" + value.text + "' is not an integer");
        if (!p.strings.empty()) pbrtFail(value.loc, quoted(p) + ": numbers mixed with names");
        p.numbers.push_back(value.number);
      } else if (isBool && (value.kind == PbrtToken::String || value.kind == PbrtToken::Word) &&
                 (value.text == "true" || value.text == "false")) {
        p.bools.push_back(value.text == "true");
      } else if (value.kind == PbrtToken::String && (isString || spectrum)) {
        if (!p.numbers.empty() || !p.strings.empty()) pbrtFail(value.loc, quoted(p) + ": expected one name");
        p.strings.push_back(value.text);
      } else {
        pbrtFail(value.loc, quoted(p) + ": '" + oneLine(value.text, 40) + "' is not a value of type " + p.type);
      }
    }
    const std::size_t count = p.numbers.size() + p.strings.size() + p.bools.size();
    if (count == 0) pbrtFail(decl.loc, quoted(p) + ": no values");
    if (numeric && p.numbers.size() % std::size_t(groupOf(p.type)) != 0)
      pbrtFail(decl.loc, quoted(p) + ": " + std::to_string(p.numbers.size()) + " numbers, not a multiple of " +
                             std::to_string(groupOf(p.type)));
    if (spectrum && !p.numbers.empty() && p.numbers.size() % 2 != 0)
      pbrtFail(decl.loc, quoted(p) + ": a spectrum's numbers are (wavelength, value) pairs, got " +
                             std::to_string(p.numbers.size()));
    out.list.push_back(std::move(p));
  }
  return out;
}

const PbrtParam* PbrtParams::find(const std::string& name) const {
  for (const PbrtParam& p : list)
    if (p.name == name) {
      p.used = true;
      return &p;
    }
  return nullptr;
}

namespace {
const PbrtParam* paramOfType(const PbrtParams& ps, const std::string& name, std::initializer_list<const char*> types) {
  const PbrtParam* p = ps.find(name);
  if (!p) return nullptr;
  bool ok = false;
  std::string names;
  for (const char* t : types) ok = ok || p->type == t, names += (names.empty() ? "" : " or ") + std::string(t);
  if (!ok) pbrtFail(p->loc, "parameter '" + p->name + "' must be of type " + names + ", got " + p->type);
  if (p->numbers.size() + p->strings.size() + p->bools.size() != 1)
    pbrtFail(p->loc, quoted(*p) + ": expected one value");
  return p;
}
}  // namespace

double PbrtParams::getFloat(const std::string& name, double fallback) const {
  const PbrtParam* p = paramOfType(*this, name, {"float"});
  return p ? p->numbers[0] : fallback;
}
int PbrtParams::getInt(const std::string& name, int fallback) const {
  const PbrtParam* p = paramOfType(*this, name, {"integer"});
  if (p && !(std::abs(p->numbers[0]) <= 2147483647.0)) pbrtFail(p->loc, quoted(*p) + ": out of the integer range");
  return p ? int(p->numbers[0]) : fallback;
}
bool PbrtParams::getBool(const std::string& name, bool fallback) const {
  const PbrtParam* p = paramOfType(*this, name, {"bool"});
  return p ? bool(p->bools[0]) : fallback;
}
std::string PbrtParams::getString(const std::string& name, const std::string& fallback) const {
  const PbrtParam* p = paramOfType(*this, name, {"string"});
  return p ? p->strings[0] : fallback;
}
std::string PbrtParams::getTexture(const std::string& name) const {
  for (const PbrtParam& p : list)
    if (p.name == name && p.type == "texture") return paramOfType(*this, name, {"texture"})->strings[0];
  return "";
}

std::vector<double> PbrtParams::getNumbers(const std::string& name, const std::vector<std::string>& types,
                                           int group) const {
  const PbrtParam* p = find(name);
  if (!p) return {};
  bool ok = false;
  std::string names;
  for (const std::string& t : types) ok = ok || p->type == t, names += (names.empty() ? "" : " or ") + t;
  if (!ok) pbrtFail(p->loc, "parameter '" + p->name + "' must be of type " + names + ", got " + p->type);
  if (p->numbers.size() % std::size_t(group) != 0)
    pbrtFail(p->loc, quoted(*p) + ": " + std::to_string(p->numbers.size()) + " numbers, not a multiple of " +
                         std::to_string(group));
  return p->numbers;
}

void PbrtParams::reportUnused(const std::string& what, std::vector<std::string>& warnings) const {
  for (const PbrtParam& p : list)
    if (!p.used) warnings.push_back(p.loc.str() + ": " + what + ": parameter " + quoted(p) + " not used by montecl, ignored");
}

bool pbrtSpectrum(const PbrtParams& ps, const std::string& name, glm::vec3& rgb, std::vector<std::string>& warnings) {
  const PbrtParam* p = ps.find(name);
  if (!p) return false;
  if (p->type == "rgb" || p->type == "color") {
    if (p->numbers.size() != 3) pbrtFail(p->loc, quoted(*p) + ": expected 3 numbers");
    rgb = glm::vec3(float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2]));
    return true;
  }
  if (p->type == "float" && p->numbers.size() == 1) {  // pbrt takes a float where a constant spectrum is meant
    rgb = glm::vec3(float(p->numbers[0]));
    return true;
  }
  if (p->type == "blackbody") {
    warnings.push_back(p->loc.str() + ": " + quoted(*p) + ": montecl does not convert blackbody spectra to colour; read as white (1, 1, 1)");
    rgb = glm::vec3(1.0f);
    return true;
  }
  if (p->type != "spectrum") pbrtFail(p->loc, "parameter '" + p->name + "' must be a spectrum (rgb, spectrum, blackbody), got " + p->type);
  if (!p->strings.empty()) {
    const std::string& s = p->strings[0];
    // "metal-Cu-eta" / "metal-Cu-k": montecl's RGB values of the metals it knows.
    if (s.rfind("metal-", 0) == 0) {
      const std::size_t dash = s.rfind('-');
      const std::string metal = s.substr(6, dash - 6), part = s.substr(dash + 1);
      glm::vec3 eta, k;
      if (dash > 6 && (part == "eta" || part == "k") && metalEtaK(metal, eta, k)) {
        rgb = part == "eta" ? eta : k;
        return true;
      }
    }
    for (const Glass& g : kGlasses)
      if (s == g.name) {
        rgb = glm::vec3(g.ior);
        return true;
      }
    warnings.push_back(p->loc.str() + ": " + quoted(*p) + ": spectrum '" + oneLine(s, 60) +
                       "' not known to montecl (it knows metal-{Au,Ag,Cu,Al,Cr}-{eta,k} and glass-*), parameter ignored");
    return false;
  }
  // (wavelength, value) pairs: the value at three wavelengths standing for R, G and B, linearly
  // interpolated (a crude reduction, exact for a constant spectrum).
  auto at = [&](double lambda) {
    const std::vector<double>& v = p->numbers;
    if (lambda <= v[0]) return v[1];
    for (std::size_t i = 2; i < v.size(); i += 2)
      if (lambda <= v[i]) {
        const double t = (lambda - v[i - 2]) / (v[i] - v[i - 2]);
        return v[i - 1] + t * (v[i + 1] - v[i - 1]);
      }
    return v[v.size() - 1];
  };
  rgb = glm::vec3(float(at(610.0)), float(at(550.0)), float(at(465.0)));
  return true;
}

bool pbrtLightSpectrum(const PbrtParams& ps, const std::string& name, glm::vec3& rgb, std::vector<std::string>& warnings) {
  const PbrtParam* p = ps.find(name);
  if (!p) return false;
  if (p->type == "spectrum" && !p->strings.empty() && p->strings[0].rfind("stdillum-", 0) == 0) {
    // pbrt's standard illuminants at luminance 1: D65 is montecl's white; the others' tint is not read.
    if (p->strings[0] != "stdillum-D65")
      warnings.push_back(p->loc.str() + ": " + quoted(*p) + ": montecl does not convert '" + oneLine(p->strings[0], 40) +
                         "' to colour; read as white (1, 1, 1) of the same luminance");
    rgb = glm::vec3(1.0f);
    return true;
  }
  if (!pbrtSpectrum(ps, name, rgb, warnings)) return false;
  if (p->type == "rgb" || p->type == "color") return true;
  const float y = 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z;
  if (y > 0.0f && std::isfinite(y)) rgb /= y;
  return true;
}

}  // namespace montecl
