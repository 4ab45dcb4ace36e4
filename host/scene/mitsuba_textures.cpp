// mitsuba_textures.cpp: Mitsuba's bitmap and checkerboard textures as montecl's (mitsuba_textures.h).
#include "scene/mitsuba_textures.h"

#include "kernels/shared/types.h"
#include "scene/load_util.h"

namespace montecl {
namespace {

std::uint32_t wrapMode(MiContext& c, const MiProps& p) {
  const std::string w = p.getString("wrap_mode", "repeat");
  if (w == "repeat") return MCL_WRAP_REPEAT;
  if (w == "mirror") return MCL_WRAP_MIRROR;
  if (w == "clamp") return MCL_WRAP_CLAMP;
  c.warn(p.locOf("wrap_mode"), "bitmap: wrap_mode '" + oneLine(w, 40) + "' not read by montecl (repeat, mirror, clamp); repeat is used");
  return MCL_WRAP_REPEAT;
}

// Mitsuba's texture coordinates have v = 0 at the image's top row, montecl's at the bottom row
// (the shapes' v is flipped as they are read, v_montecl = 1 - v_mitsuba). Mitsuba's to_uv maps
// (u, v) to (a u + b v + c, d u + e v + f) in its convention; in montecl's that is
// u' = a u - b v + (b + c), v' = -d u + e v + (1 - e - f).
void uvTransform(const glm::dmat4& m, TextureSampling& s) {
  const double a = m[0][0], b = m[1][0], cc = m[3][0], d = m[0][1], e = m[1][1], f = m[3][1];
  s.row0 = glm::vec3(float(a), float(-b), float(b + cc));
  s.row1 = glm::vec3(float(-d), float(e), float(1.0 - e - f));
}

}  // namespace

MiTexture miTexture(MiContext& c, const MiElem& texture, const std::string& role) {
  const MiProps p(c.doc, texture);
  MiTexture t;
  const std::string what = "texture \"" + oneLine(p.type, 40) + "\"";
  if (p.type == "bitmap") {
    const std::string name = p.getString("filename", "");
    if (name.empty()) mitsubaFail(p.loc, "bitmap: 'filename' is required");
    t.file = c.doc.resolve(name);
    const std::string filter = p.getString("filter_type", "bilinear");
    if (filter != "bilinear")
      c.warn(p.locOf("filter_type"), "bitmap: filter_type '" + oneLine(filter, 40) + "': montecl filters textures bilinearly (trilinear between mip levels)");
    if (p.getBool("raw", false) && role != "opacity" && role != "bump")
      c.warn(p.locOf("raw"), "bitmap: raw: montecl decodes 8-bit colour textures from sRGB in every colour slot");
    t.sampling.wrapS = t.sampling.wrapT = wrapMode(c, p);
    bool given = false;
    const glm::dmat4 uv = p.getTransform("to_uv", &given);
    if (given) uvTransform(uv, t.sampling);
    p.find("format");  // Mitsuba's storage precision: montecl stores half floats
    if (!fileProblem(t.file).empty()) {
      MissingTexture m;
      const MiLoc at = p.locOf("filename");
      m.file = at.file;
      m.where = "line " + std::to_string(at.line);
      m.lead = "bitmap '" + oneLine(t.file, 120) + "' cannot be opened";
      m.brief = oneLine(t.file, 120);
      noteMissingTexture(c.scene.missingTextures, m);
      t.file.clear();
    } else {
      c.scene.inputFiles.push_back(t.file);
    }
  } else if (p.type == "checkerboard") {
    glm::vec3 a(0.4f), b(0.2f);  // Mitsuba's defaults
    miColourInto(c, p, "color0", &a, nullptr, nullptr);
    miColourInto(c, p, "color1", &b, nullptr, nullptr);
    p.find("to_uv");
    t.value = 0.5f * (a + b);
    c.warn(p.loc, what + ": montecl has no procedural textures; its mean colour is used");
  } else {
    c.warn(p.loc, what + " not read by montecl (it reads bitmap, checkerboard); grey 0.5 is used");
    t.value = glm::vec3(0.5f);
    return t;
  }
  p.reportUnused(what, c.warnings);
  return t;
}

bool miColourInto(MiContext& c, const MiProps& p, const std::string& name, glm::vec3* value, std::string* file,
                  TextureSampling* sampling) {
  const std::optional<MiColour> col = p.getColour(name, c.warnings);
  if (!col) return false;
  if (!col->texture) {
    *value = col->value;
    return true;
  }
  const MiTexture t = miTexture(c, col->texture, name);
  if (t.file.empty()) {
    *value = t.value;
  } else if (file) {
    *value = glm::vec3(1.0f);
    *file = t.file;
    if (sampling) *sampling = t.sampling;
  } else {
    c.warn(c.doc.loc(col->texture), "'" + name + "': montecl takes no texture here; white (1) is used");
    *value = glm::vec3(1.0f);
  }
  return true;
}

}  // namespace montecl
