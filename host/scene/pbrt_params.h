// pbrt_params.h: a pbrt-v4 directive's parameter list ("float fov" [ 45 ] "rgb L" [ 1 1 1 ] ...):
// read from the tokenizer, checked per type, asked for by name, and the ones nobody asked for
// reported as pbrt's ReportUnused does (here as warnings). Reads tokens, writes nothing else.
#pragma once
#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "scene/pbrt_tokenizer.h"

namespace montecl {

struct PbrtParam {
  std::string type, name;           // "float", "fov"
  std::vector<double> numbers;      // numeric types
  std::vector<std::string> strings; // string, texture, spectrum given by name or file
  std::vector<bool> bools;          // bool
  PbrtLoc loc;                      // where "type name" is
  mutable bool used = false;
};

class PbrtParams {
 public:
  std::vector<PbrtParam> list;
  PbrtLoc loc;  // the directive's

  const PbrtParam* find(const std::string& name) const;  // marks it used
  // The one value of a parameter of that type, or fallback when absent; a present parameter of
  // another type or count is a pbrtFail at its location.
  double getFloat(const std::string& name, double fallback) const;
  int getInt(const std::string& name, int fallback) const;
  bool getBool(const std::string& name, bool fallback) const;
  std::string getString(const std::string& name, const std::string& fallback) const;
  // Numbers of a type given in groups of `group` (point3: 3): empty when absent.
  std::vector<double> getNumbers(const std::string& name, const std::vector<std::string>& types, int group) const;
  // The name of the texture a parameter names ("texture reflectance" "name"), "" when not a texture.
  std::string getTexture(const std::string& name) const;
  // Marks a parameter read without looking at it (the film's filename: the command line decides).
  void ignore(const std::string& name) const { find(name); }
  // Appends one warning per parameter never asked for: "<loc>: <what>: parameter 'type name' not
  // used by montecl, ignored".
  void reportUnused(const std::string& what, std::vector<std::string>& warnings) const;
};

// Reads parameters while the next token is a string; the directive's location given.
PbrtParams readPbrtParams(PbrtTokenizer& tok, const PbrtLoc& directive);

// A pbrt spectrum parameter (rgb, spectrum by values or by name, blackbody) as linear RGB; false
// when absent. Named metal spectra become montecl's RGB eta/k of that metal, named glasses their
// index at about 550 nm (all three channels); blackbody and unknown names are warned about.
bool pbrtSpectrum(const PbrtParams& p, const std::string& name, glm::vec3& rgb, std::vector<std::string>& warnings);

// A light's emission spectrum as pbrt-v4 means it: an RGB value is the radiance (intensity,
// irradiance) itself; any other spectrum (values, a name, blackbody) is normalised by pbrt to
// luminance 1 before the light's scale multiplies it, so its RGB reduction is scaled to luminance 1.
bool pbrtLightSpectrum(const PbrtParams& p, const std::string& name, glm::vec3& rgb, std::vector<std::string>& warnings);

}  // namespace montecl
