// mitsuba_props.h: one Mitsuba plugin element's properties (<float name= value=/>, <rgb>, <point>,
// <transform>, nested <texture>, <ref>, ...): checked per type, asked for by name, and the ones
// nobody asked for reported as warnings. Reads elements of a MiDocument, writes nothing else.
#pragma once
#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

#include "scene/mitsuba_xml.h"

namespace montecl {

// A colour-valued property: a constant, or a texture element (a nested <texture> or the element a
// <ref> names) whose value multiplies nothing (Mitsuba textures carry their own scale).
struct MiColour {
  glm::vec3 value{1.0f};
  MiElem texture;  // empty: the constant
};

class MiProps {
 public:
  MiProps(const MiDocument& doc, const MiElem& plugin);

  const MiDocument& doc;
  MiElem elem;
  std::string type;  // the plugin's type attribute
  MiLoc loc;

  // The property element of that name (marked read), or an empty MiElem.
  MiElem find(const std::string& name) const;
  MiLoc locOf(const std::string& name) const;  // the property's place (the plugin's when absent)
  double getFloat(const std::string& name, double fallback) const;
  int getInt(const std::string& name, int fallback) const;
  bool getBool(const std::string& name, bool fallback) const;
  std::string getString(const std::string& name, const std::string& fallback) const;
  // <point>/<vector> (x y z attributes or value="x y z").
  std::optional<glm::dvec3> getPoint(const std::string& name) const;
  // <transform name=...>: the product of its steps (mitsuba_transform.h); identity when absent.
  glm::dmat4 getTransform(const std::string& name, bool* given = nullptr) const;
  // <rgb>, <spectrum>, <float> (grey), a nested <texture> or <ref>: nullopt when absent.
  std::optional<MiColour> getColour(const std::string& name, std::vector<std::string>& warnings) const;
  // The nested plugin elements with tag `tag` (bsdf, emitter, texture without a name, ...) in
  // order, <ref>s to such elements resolved; each marked read.
  std::vector<MiElem> objects(const std::string& tag) const;
  // One warning per property or nested element nobody asked for: "<loc>: <what>: property 'name'
  // not read by montecl, ignored".
  void reportUnused(const std::string& what, std::vector<std::string>& warnings) const;

 private:
  struct Entry {
    MiElem elem;
    std::string name;  // Mitsuba 3 spelling; "" for a nested plugin without a name
    mutable bool used = false;
  };
  std::vector<Entry> entries_;
  std::string value(const MiElem& e) const;
  std::vector<double> numbers(const MiElem& e, const std::string& text) const;
};

// A property's numbers: "1 2 3" or "1, 2, 3" (an empty or malformed value: mitsubaFail at loc).
std::vector<double> miNumbers(const MiLoc& loc, const std::string& what, const std::string& text);

}  // namespace montecl
