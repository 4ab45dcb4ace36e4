// mtl_materials.cpp: MTL files for the OBJ loader (see mtl_materials.h): opening, the line scan,
// conversion to MaterialDesc with validation, texture paths, one warning per unused kind.
#include "scene/mtl_materials.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>
#include <utility>

#include "scene/glossy_material.h"
#include "scene/load_util.h"

namespace montecl {
namespace {

bool isBlank(char c) { return c == ' ' || c == '\t'; }

// The three spellings of the bump map statement (tinyobjloader reads each as bump_texname).
bool isBumpKey(const std::string& key) { return key == "bump" || key == "map_bump" || key == "map_Bump"; }

// What montecl reads from an MTL; every other statement is reported once per kind.
bool isUsed(const std::string& key) {
  // Pm / Pr always pick a kind; illum and Ni only for glass (scanMtl, mtlKind).
  static const std::set<std::string> used = {"newmtl", "Kd", "Ke", "Ks", "Ns", "map_Kd", "map_d", "map_Ke", "Pm", "Pr", "norm",
                                           "bump", "map_bump", "map_Bump"};
  return used.count(key) > 0;
}

std::string unusedText(const std::string& key) {
  static const std::map<std::string, std::string> what = {
      {"Ka", "ambient colour"},          {"illum", "illumination model"},  {"Ni", "index of refraction"},
      {"Tf", "transmission filter"},     {"map_Ka", "ambient texture"},    {"map_Ks", "specular texture"},
      {"map_Ns", "exponent texture"},    {"disp", "displacement map"},
      {"refl", "reflection map"},        {"Pr", "PBR roughness"},
      {"Pm", "PBR metallic"},            {"map_Pr", "roughness texture"},  {"map_Pm", "metallic texture"}};
  auto it = what.find(key);
  return "'" + key + "'" + (it == what.end() ? "" : " (" + it->second + ")") + " not used by montecl, ignored";
}

// Scans the MTL text the way tinyobjloader splits it (lines end at \n, \r\n or \r; blocks start at
// `newmtl`; the statements before the first one go to a block that is dropped, unless there is no
// `newmtl` at all), recording the first line of each statement per block and the unused kinds.
void scanMtl(const std::string& text, MtlFile& f) {
  MtlBlock current;
  bool named = false;
  std::size_t line = 0;
  // illum 4, 6, 7 (glass) with Ni makes a dielectric (mtlKind): those are used; any other illum,
  // and Ni in a block that is not glass, are reported, once the block's end shows which it is.
  bool glass = false;
  std::vector<std::pair<std::string, std::string>> pending;  // (key, where) of illum / Ni
  const auto endBlock = [&]() {
    for (const auto& k : pending)
      if (!glass) f.unused.add(k.first, k.second, unusedText(k.first));
    pending.clear();
    glass = false;
  };
  for (std::size_t p = 0; p < text.size();) {
    std::size_t eol = text.find_first_of("\r\n", p);
    if (eol == std::string::npos) eol = text.size();
    std::string s = text.substr(p, eol - p);
    p = eol + (text.compare(eol, 2, "\r\n") == 0 ? 2 : 1);
    ++line;
    std::size_t b = 0;
    while (b < s.size() && isBlank(s[b])) ++b;
    while (!s.empty() && isBlank(s.back())) s.pop_back();
    if (b >= s.size() || s[b] == '#') continue;
    std::size_t e = b;
    while (e < s.size() && !isBlank(s[e])) ++e;
    const std::string key = s.substr(b, e - b);
    if (key == "newmtl" && e < s.size()) {
      endBlock();
      if (named) f.blocks.push_back(current);
      current = MtlBlock{};
      named = true;
    }
    current.line.emplace(key, line);
    const std::string where = lineWhere(line);
    std::istringstream rest(s.substr(e));
    if (key == "d" || key == "Tr") {
      double v = key == "d" ? 1.0 : 0.0;
      rest >> v;
      if (v != (key == "d" ? 1.0 : 0.0))
        f.unused.add("dissolve", where,
                     "'" + key + "' (constant opacity) not used by montecl: only map_d cuts out, ignored");
    } else if (key == "illum" || key == "Ni") {
      int v = 0;
      if (key == "illum" && (rest >> v) && (v == 4 || v == 6 || v == 7)) glass = true;
      pending.emplace_back(key, where);
    } else if (!isUsed(key)) {
      f.unused.add(key, where, unusedText(key));
    } else if (key == "map_Kd" || key == "map_d") {
      std::string token;
      while (rest >> token)
        if (token.size() > 1 && token[0] == '-') {
          f.unused.add("texture options", where,
                       "texture option '" + token + "' not used by montecl (textures repeat, unscaled), ignored");
          break;
        }
    } else if (isBumpKey(key) || key == "norm") {
      // -bm is the height (normal) scale; the other options (offset, scale, channel) are not read.
      std::string token;
      while (rest >> token)
        if (token == "-bm") {
          rest >> token;
          current.bm.emplace(key, token);
        } else if (isBumpKey(key) && token.size() > 1 && token[0] == '-') {
          f.unused.add("bump options", where,
                       "bump map option '" + token + "' not used by montecl (only -bm, the height scale), ignored");
          break;
        }
    }
  }
  endBlock();
  f.blocks.push_back(current);
}

bool validColor(const glm::vec3& c, float hi) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(c[k]) || c[k] < 0.0f || c[k] > hi) return false;
  return true;
}

glm::vec3 toVec3(const tinyobj::real_t* c) {
  return glm::vec3(static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]));
}

// Where the statements of one material are: the MTL file and, when the scan matches tinyobj's
// materials, their lines.
struct MaterialSource {
  std::string file;
  const MtlBlock* block = nullptr;
  std::string name;
  bool has(const std::string& key) const { return block && block->line.count(key); }
  std::string where(const std::string& key) const {
    return has(key) ? lineWhere(block->line.at(key)) : std::string();
  }
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    loadFail(file, where(key), "material '" + oneLine(name, 60) + "': " + problem);
  }
};

MaterialSource sourceOf(const std::string& objPath, const std::vector<MtlFile>& files, std::size_t index,
                        const std::string& name) {
  for (const MtlFile& f : files)
    if (index >= f.firstMaterial && index < f.firstMaterial + f.count) {
      const MtlBlock* b = f.blocks.size() == f.count ? &f.blocks[index - f.firstMaterial] : nullptr;
      return {f.path, b, name};
    }
  return {objPath, nullptr, name};
}

// Where the textures of an OBJ's materials that could not be opened go (scene.missingTextures, so
// that one message names them all: a scene with ten misspelt names needs one run to fix, not ten),
// and where the case-insensitive matches used instead of what was written are warned about.
struct TextureLookup {
  Scene* scene = nullptr;
  std::vector<std::string>* warnings = nullptr;
};

// A texture named by key, opened beside the MTL; a name written with backslashes (Windows
// exporters) is tried with slashes, then either is tried ignoring case (with a warning), when it is
// not found as written. "" when none opens (recorded in look).
std::string texturePath(const MaterialSource& src, const std::string& key, const std::string& name, TextureLookup& look) {
  if (name.empty()) src.fail(key, key + " needs a file name");
  const std::string path = besideFile(src.file, name);
  const std::string problem = fileProblem(path);
  if (problem.empty()) return path;
  std::string slashed = name;
  std::replace(slashed.begin(), slashed.end(), '\\', '/');
  if (slashed != name && fileProblem(besideFile(src.file, slashed)).empty()) return besideFile(src.file, slashed);
  const std::string found = findIgnoringCase(besideFile(src.file, slashed));
  const std::string where = src.where(key);
  const std::string at = src.file + (where.empty() ? "" : ": " + where);
  if (!found.empty()) {
    if (look.warnings)
      look.warnings->push_back(at + ": material '" + oneLine(src.name, 60) + "': " + key + " '" + oneLine(name, 200) +
                               "' not found as written; using '" + found + "' (the names differ in case)");
    return found;
  }
  noteMissingTexture(look.scene->missingTextures,
      {src.file, where,
       "material '" + oneLine(src.name, 60) + "': " + key + " '" + oneLine(name, 200) + "': cannot open '" + path + "': " + problem,
       (where.empty() ? "" : where + " ") + key + " '" + oneLine(name, 200) + "'"});
  return "";
}

// The material kind of an MTL material: illum 4, 6 or 7 (glass, refraction) with Ni -> dielectric
// of ior Ni; Pm or Pr (the PBR extension) -> metal_rough (base Kd, metallic Pm, default 0;
// roughness Pr, default 1); otherwise diffuse (Kd + Ks/Ns).
void mtlKind(const tinyobj::material_t& m, const MaterialSource& src, MaterialDesc& d) {
  if ((m.illum == 4 || m.illum == 6 || m.illum == 7) && src.has("Ni")) {
    d.kind = MCL_MATERIAL_dielectric;
    d.ior = static_cast<float>(m.ior);
    if (!(d.ior > 0.0f && std::isfinite(d.ior))) src.fail("Ni", "Ni must be a finite number > 0");
  } else if (src.has("Pm") || src.has("Pr")) {
    d.kind = MCL_MATERIAL_metal_rough;
    d.metallic = src.has("Pm") ? static_cast<float>(m.metallic) : 0.0f;
    d.roughness = src.has("Pr") ? static_cast<float>(m.roughness) : 1.0f;
    if (!(d.metallic >= 0.0f && d.metallic <= 1.0f)) src.fail("Pm", "Pm must be in [0, 1]");
    if (!(d.roughness >= 0.0f && d.roughness <= 1.0f)) src.fail("Pr", "Pr must be in [0, 1]");
  }
}

// The -bm of statement key (norm, bump) as written and as tinyobjloader read it (value): a number
// that is finite, else InputError naming the line.
void checkMultiplier(const MaterialSource& src, const std::string& key, float value) {
  std::string text;
  if (src.block && src.block->bm.count(key)) {
    text = src.block->bm.at(key);
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v) || !std::isfinite(float(v))) value = NAN;
  }
  if (!std::isfinite(value))
    src.fail(key, key + " -bm " + (text.empty() ? "" : "'" + oneLine(text, 40) + "' ") + "must be a finite number");
}

// The MTL text with one blank between `newmtl` and the name: tinyobjloader keeps any further blanks
// in the name ("newmtl  RearLights" names " RearLights"), while `usemtl` skips them, so the OBJ's
// `usemtl RearLights` found no material. Lines (and their numbers) stay as they are.
std::string singleSpacedNewmtl(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t p = 0; p < text.size();) {
    std::size_t eol = text.find_first_of("\r\n", p);
    if (eol == std::string::npos) eol = text.size();
    std::size_t b = p;
    while (b < eol && isBlank(text[b])) ++b;
    if (text.compare(b, 6, "newmtl") == 0 && b + 7 < eol && isBlank(text[b + 6]) && isBlank(text[b + 7])) {
      std::size_t name = b + 6;
      while (name < eol && isBlank(text[name])) ++name;
      out.append(text, p, b + 7 - p);  // up to and with the first blank
      p = name;
    }
    const std::size_t next = std::min(text.size(), eol + (text.compare(eol, 2, "\r\n") == 0 ? 2 : 1));
    out.append(text, p, next - p);
    p = next;
  }
  return out;
}

// tinyobjloader's warnings while reading one MTL, as warnings of that MTL: "Both `d` and `Tr`
// parameters defined for "NAME". Use the value of `d` for dissolve (line N in .mtl.)" becomes
// "<mtl>: line N: material 'NAME' gives both d and Tr (opacity, written twice): Tr ignored".
void addMtlParserWarnings(const std::string& text, MtlFile& f) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    if (line.find("Both `d` and `Tr`") == std::string::npos) {
      f.unused.add("parser: " + line.substr(0, 24), "", line);
      continue;
    }
    const std::size_t q0 = line.find('"'), q1 = q0 == std::string::npos ? q0 : line.find('"', q0 + 1);
    const std::string name = q1 == std::string::npos ? std::string() : line.substr(q0 + 1, q1 - q0 - 1);
    const std::size_t at = line.find("(line ");
    std::string where;
    if (at != std::string::npos) {
      const std::size_t end = line.find_first_not_of("0123456789", at + 6);
      where = "line " + line.substr(at + 6, end == std::string::npos ? std::string::npos : end - at - 6);
    }
    f.unused.add("both d and Tr", where,
                 "material '" + name + "' gives both d and Tr (opacity, written twice): Tr ignored");
  }
}

}  // namespace

bool MtlReader::operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                           std::map<std::string, int>* matMap, std::string* warn, std::string* err) {
  const std::string path = besideFile(objPath_, name);
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    missing.push_back(path);
    return false;
  }
  // Only regular files: a FIFO would block the open, /dev/zero would be read until memory runs out.
  if (!S_ISREG(st.st_mode)) {
    if (notRegular.empty()) notRegular = path + "': " + (S_ISDIR(st.st_mode) ? "is a directory" : "not a regular file");
    return false;
  }
  MtlFile f{path, materials->size(), 0, {}, KindWarnings(path)};
  const std::string text = readWholeFile(path);
  scanMtl(text, f);
  std::istringstream in(singleSpacedNewmtl(text));
  // tinyobj's own warnings about the MTL (both d and Tr, ...) are the MTL's, not the OBJ's.
  std::string mtlWarn;
  tinyobj::LoadMtl(matMap, materials, &in, &mtlWarn, err);
  addMtlParserWarnings(mtlWarn, f);
  (void)warn;
  f.count = materials->size() - f.firstMaterial;
  files.push_back(std::move(f));
  return true;
}

std::uint32_t appendMtlMaterials(const std::string& objPath, const std::vector<tinyobj::material_t>& mats,
                                 const std::vector<MtlFile>& files, Scene& scene,
                                 std::vector<std::string>* warnings) {
  for (const MtlFile& f : files) f.unused.flush(warnings);
  auto base = static_cast<std::uint32_t>(scene.materials.size());
  std::set<std::string> textures;
  GlossyScaling scaled;  // Kd + Ks > 1: one warning per OBJ
  std::string scaledAt;  // where the first scaled material is
  TextureLookup look{&scene, warnings};
  std::map<std::string, KindWarnings> bothMaps;  // per MTL: materials with both norm and bump
  const std::size_t missingBefore = scene.missingTextures.size();
  for (std::size_t i = 0; i < mats.size(); ++i) {
    const tinyobj::material_t& m = mats[i];
    const MaterialSource src = sourceOf(objPath, files, i, m.name);
    MaterialDesc d;
    d.name = m.name;
    d.kind = MCL_MATERIAL_diffuse;  // Kd + Ks/Ns, unless mtlKind (below) finds glass or PBR keys
    d.albedo = toVec3(m.diffuse);
    d.emission = toVec3(m.emission);
    d.specular = toVec3(m.specular);
    d.specularExponent = static_cast<float>(m.shininess);
    if (!validColor(d.albedo, INFINITY)) src.fail("Kd", "Kd must be finite and >= 0");
    if (!validColor(d.emission, INFINITY)) src.fail("Ke", "Ke must be finite and >= 0");
    if (!validColor(d.specular, 1.0f)) src.fail("Ks", "Ks components must be in [0, 1]");
    if (!std::isfinite(d.specularExponent) || d.specularExponent < 0.0f) src.fail("Ns", "Ns must be finite and >= 0");
    if (src.block && !src.has("Ns")) d.specularExponent = 0.0f;  // tinyobj's default is 1
    mtlKind(m, src, d);
    // A texture that cannot be opened is "" (recorded in look): the material as if it had none.
    if (!m.diffuse_texname.empty() || src.has("map_Kd")) {
      d.albedoTexture = texturePath(src, "map_Kd", m.diffuse_texname, look);
      if (src.block && !src.has("Kd") && !d.albedoTexture.empty()) d.albedo = glm::vec3(1.0f);  // the texture as it is (tinyobj: 0.6)
    }
    if (!m.alpha_texname.empty() || src.has("map_d")) d.alphaTexture = texturePath(src, "map_d", m.alpha_texname, look);
    if (!d.albedoTexture.empty() && !src.has("map_d") && m.alpha_texname.empty()) {
      const std::string where = src.where("map_Kd");
      d.cutoutHint = oneLine(src.file, 4096) + (where.empty() ? "" : ": " + where) + ": material '" + oneLine(m.name, 60) +
                     "': map_Kd '" + oneLine(m.diffuse_texname, 200) + "'";
    }
    // map_Ke multiplies Ke; without a Ke statement the texture is the emission as it is (Ke 1).
    if (!m.emissive_texname.empty() || src.has("map_Ke")) {
      const glm::vec3 ke = src.block && !src.has("Ke") ? glm::vec3(1.0f) : d.emission;
      if (ke != glm::vec3(0.0f)) d.emissionTexture = texturePath(src, "map_Ke", m.emissive_texname, look);
      if (!d.emissionTexture.empty()) d.emission = ke;
    }
    // norm: a tangent-space normal map (linear), -bm its scale (glTF's normalTexture scale).
    if (!m.normal_texname.empty() || src.has("norm")) {
      d.normalTexture = texturePath(src, "norm", m.normal_texname, look);
      d.normalScale = static_cast<float>(m.normal_texopt.bump_multiplier);
      checkMultiplier(src, "norm", d.normalScale);
    }
    // bump: a height map (linear), -bm its scale: the surface is displaced by -bm x height world
    // units along the shading normal (bump_map.h). Beside a normal map it is not used (usesBumpMap).
    std::string bumpKey = "bump";
    for (const char* k : {"bump", "map_bump", "map_Bump"})
      if (src.has(k) && (!src.has(bumpKey) || src.block->line.at(k) < src.block->line.at(bumpKey))) bumpKey = k;
    if (!m.bump_texname.empty() || src.has(bumpKey)) {
      d.bumpScale = static_cast<float>(m.bump_texopt.bump_multiplier);
      checkMultiplier(src, bumpKey, d.bumpScale);
      d.bumpTexture = texturePath(src, bumpKey, m.bump_texname, look);
      if (!d.normalTexture.empty() && !d.bumpTexture.empty()) {
        auto it = bothMaps.try_emplace(src.file, src.file).first;
        it->second.add("norm and bump", src.where(bumpKey),
                       "material '" + oneLine(m.name, 60) + "': both norm and " + bumpKey +
                           ": the normal map is used, the bump map ignored");
      }
    }
    for (const std::string* t : {&d.albedoTexture, &d.alphaTexture, &d.emissionTexture, &d.normalTexture,
                                 &d.bumpTexture})
      if (!t->empty() && textures.insert(*t).second) scene.inputFiles.push_back(*t);
    const std::string where = "material '" + oneLine(m.name, 60) + "'";
    const float factor = checkGlossyMaterial(oneLine(src.file, 4096), where, d);
    if (factor != 1.0f && scaled.count == 0) {  // the warning names the MTL and the first one's Ks line
      const std::string line = src.where("Ks");
      scaledAt = oneLine(src.file, 4096) + (line.empty() ? "" : ": " + line);
    }
    scaled.note(oneLine(m.name, 60), factor);
    scene.materials.push_back(d);
  }
  failOnMissingTextures(scene, missingBefore);
  for (const auto& b : bothMaps) b.second.flush(warnings);
  scaled.warn(scaledAt, warnings);
  return base;
}

}  // namespace montecl
