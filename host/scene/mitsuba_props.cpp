// mitsuba_props.cpp: typed access to a Mitsuba plugin element's properties (mitsuba_props.h).
#include "scene/mitsuba_props.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "scene/load_util.h"
#include "scene/mitsuba_transform.h"

namespace montecl {
namespace {

// Tags that hold one value; every other child element is a nested plugin (or a <ref> to one).
bool isValueTag(const std::string& t) {
  return t == "float" || t == "integer" || t == "boolean" || t == "string" || t == "rgb" || t == "srgb" ||
         t == "spectrum" || t == "point" || t == "vector" || t == "transform";
}

float srgbDecode(double c) {
  return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

}  // namespace

std::vector<double> miNumbers(const MiLoc& loc, const std::string& what, const std::string& text) {
  std::vector<double> out;
  const char* p = text.c_str();
  while (*p) {
    while (*p == ' ' || *p == ',' || *p == '\t' || *p == '\n' || *p == '\r') ++p;
    if (!*p) break;
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(p, &end);
    if (end == p) mitsubaFail(loc, what + ": '" + oneLine(text, 60) + "' is not a list of numbers");
    if (!std::isfinite(v) || errno == ERANGE) mitsubaFail(loc, what + ": '" + oneLine(text, 60) + "' holds a number out of range");
    out.push_back(v);
    p = end;
  }
  if (out.empty()) mitsubaFail(loc, what + ": no value");
  return out;
}

MiProps::MiProps(const MiDocument& d, const MiElem& plugin) : doc(d), elem(plugin), loc(d.loc(plugin)) {
  type = d.attr(plugin, "type");
  for (const MiElem& c : d.children(plugin)) {
    std::string name = d.attr(c, "name");
    if (d.camelCase()) name = miSnakeCase(name);
    entries_.push_back(Entry{c, name});
  }
}

MiElem MiProps::find(const std::string& name) const {
  MiElem found;
  for (const Entry& e : entries_)
    if (!e.name.empty() && e.name == name) {
      e.used = true;
      found = e.elem;  // Mitsuba keeps the last of a repeated property
    }
  return found;
}

MiLoc MiProps::locOf(const std::string& name) const {
  const MiElem e = find(name);
  return e ? doc.loc(e) : loc;
}

std::string MiProps::value(const MiElem& e) const {
  if (!doc.hasAttr(e, "value")) mitsubaFail(doc.loc(e), "<" + e.tag() + " name=\"" + doc.attr(e, "name") + "\"> needs a 'value'");
  return doc.attr(e, "value");
}

std::vector<double> MiProps::numbers(const MiElem& e, const std::string& text) const {
  return miNumbers(doc.loc(e), "'" + doc.attr(e, "name") + "'", text);
}

double MiProps::getFloat(const std::string& name, double fallback) const {
  const MiElem e = find(name);
  if (!e) return fallback;
  if (e.tag() != "float" && e.tag() != "integer")
    mitsubaFail(doc.loc(e), "'" + name + "' must be a <float>, got <" + e.tag() + ">");
  const std::vector<double> v = numbers(e, value(e));
  if (v.size() != 1) mitsubaFail(doc.loc(e), "'" + name + "' must be one number");
  return v[0];
}

int MiProps::getInt(const std::string& name, int fallback) const {
  const MiElem e = find(name);
  if (!e) return fallback;
  if (e.tag() != "integer") mitsubaFail(doc.loc(e), "'" + name + "' must be an <integer>, got <" + e.tag() + ">");
  const std::vector<double> v = numbers(e, value(e));
  if (v.size() != 1 || v[0] != std::floor(v[0]) || std::fabs(v[0]) > 2147483647.0)
    mitsubaFail(doc.loc(e), "'" + name + "' must be one integer in [-2147483647, 2147483647]");
  return int(v[0]);
}

bool MiProps::getBool(const std::string& name, bool fallback) const {
  const MiElem e = find(name);
  if (!e) return fallback;
  if (e.tag() != "boolean") mitsubaFail(doc.loc(e), "'" + name + "' must be a <boolean>, got <" + e.tag() + ">");
  const std::string v = value(e);
  if (v == "true" || v == "1") return true;
  if (v == "false" || v == "0") return false;
  mitsubaFail(doc.loc(e), "'" + name + "' must be true or false, got '" + oneLine(v, 40) + "'");
}

std::string MiProps::getString(const std::string& name, const std::string& fallback) const {
  const MiElem e = find(name);
  if (!e) return fallback;
  if (e.tag() != "string") mitsubaFail(doc.loc(e), "'" + name + "' must be a <string>, got <" + e.tag() + ">");
  return value(e);
}

std::optional<glm::dvec3> MiProps::getPoint(const std::string& name) const {
  const MiElem e = find(name);
  if (!e) return std::nullopt;
  if (e.tag() != "point" && e.tag() != "vector")
    mitsubaFail(doc.loc(e), "'" + name + "' must be a <point> or <vector>, got <" + e.tag() + ">");
  if (doc.hasAttr(e, "value")) {
    const std::vector<double> v = numbers(e, value(e));
    if (v.size() != 3) mitsubaFail(doc.loc(e), "'" + name + "' must have 3 values");
    return glm::dvec3(v[0], v[1], v[2]);
  }
  glm::dvec3 p(0.0);
  for (int i = 0; i < 3; ++i) {
    const char* axis[] = {"x", "y", "z"};
    if (doc.hasAttr(e, axis[i])) p[i] = numbers(e, doc.attr(e, axis[i]))[0];
  }
  return p;
}

glm::dmat4 MiProps::getTransform(const std::string& name, bool* given) const {
  const MiElem e = find(name);
  if (given) *given = bool(e);
  if (!e) return glm::dmat4(1.0);
  if (e.tag() != "transform") mitsubaFail(doc.loc(e), "'" + name + "' must be a <transform>, got <" + e.tag() + ">");
  return miTransform(doc, e);
}

std::optional<MiColour> MiProps::getColour(const std::string& name, std::vector<std::string>& warnings) const {
  const MiElem e = find(name);
  if (!e) return std::nullopt;
  MiColour c;
  const std::string t = e.tag();
  if (t == "texture") {
    c.texture = e;
  } else if (t == "ref") {
    c.texture = doc.byId(doc.attr(e, "id"));
    if (!c.texture) mitsubaFail(doc.loc(e), "<ref id=\"" + oneLine(doc.attr(e, "id"), 60) + "\">: no element has that id");
    if (c.texture.tag() != "texture")
      mitsubaFail(doc.loc(e), "'" + name + "' refers to a <" + c.texture.tag() + ">, not a <texture>");
  } else if (t == "float") {
    c.value = glm::vec3(float(getFloat(name, 1.0)));
  } else if (t == "rgb" || t == "srgb") {
    const std::vector<double> v = numbers(e, value(e));
    if (v.size() != 1 && v.size() != 3) mitsubaFail(doc.loc(e), "'" + name + "' must have 1 or 3 values");
    for (int i = 0; i < 3; ++i) c.value[i] = float(v[v.size() == 3 ? std::size_t(i) : 0]);
    if (t == "srgb")
      for (int i = 0; i < 3; ++i) c.value[i] = srgbDecode(c.value[i]);
  } else if (t == "spectrum") {
    if (doc.hasAttr(e, "filename")) {
      warnings.push_back(doc.loc(e).str() + ": '" + name + "': a spectrum file is not read by montecl; white (1) is used");
      return c;
    }
    const std::string text = value(e);
    if (text.find(':') == std::string::npos) {
      const std::vector<double> v = numbers(e, text);
      if (v.size() != 1) mitsubaFail(doc.loc(e), "'" + name + "': a <spectrum> value is one number or wavelength:value pairs");
      c.value = glm::vec3(float(v[0]));
    } else {
      std::string flat = text;
      for (char& ch : flat)
        if (ch == ':') ch = ' ';
      const std::vector<double> v = numbers(e, flat);
      if (v.size() % 2 != 0) mitsubaFail(doc.loc(e), "'" + name + "': wavelength:value pairs expected");
      double sum = 0.0;
      for (std::size_t i = 1; i < v.size(); i += 2) sum += v[i];
      c.value = glm::vec3(float(sum / double(v.size() / 2)));
      warnings.push_back(doc.loc(e).str() + ": '" + name + "': montecl renders RGB; this sampled spectrum is read as grey, its mean value");
    }
  } else {
    mitsubaFail(doc.loc(e), "'" + name + "' must be a colour (<rgb>, <spectrum>, <float> or a texture), got <" + t + ">");
  }
  return c;
}

std::vector<MiElem> MiProps::objects(const std::string& tag) const {
  std::vector<MiElem> out;
  for (const Entry& e : entries_) {
    MiElem target = e.elem;
    if (e.elem.tag() == "ref") {
      if (!e.name.empty()) continue;  // a named <ref> is a property (getColour)
      target = doc.byId(doc.attr(e.elem, "id"));
      if (!target) mitsubaFail(doc.loc(e.elem), "<ref id=\"" + oneLine(doc.attr(e.elem, "id"), 60) + "\">: no element has that id");
    } else if (isValueTag(e.elem.tag()) || !e.name.empty()) {
      continue;
    }
    if (target.tag() != tag) continue;
    e.used = true;
    out.push_back(target);
  }
  return out;
}

void MiProps::reportUnused(const std::string& what, std::vector<std::string>& warnings) const {
  for (const Entry& e : entries_) {
    if (e.used) continue;
    const std::string label = e.name.empty() ? "<" + e.elem.tag() + ">" : "property '" + e.name + "'";
    warnings.push_back(doc.loc(e.elem).str() + ": " + what + ": " + label + " not read by montecl, ignored");
  }
}

}  // namespace montecl
