// obj_mesh.cpp: loads one OBJ (+ its MTL files) into a Scene. A fast pre-scan of the OBJ text
// catches what tinyobjloader silently accepts (binary data, non-OBJ text, NaN/inf coordinates,
// out-of-range face indices) and reports it with a line number; tinyobjloader then parses the
// same in-memory text, triangulates, and reads the materials (Kd = albedo, Ke = emission).
#include <tiny_obj_loader.h>

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "scene/glossy_material.h"
#include "scene/scene.h"
#include "util/errors.h"

namespace montecl {
namespace {

const char* const kDefaultMaterialName = "<default>";

// Replaces control characters so that a message stays on one line.
std::string oneLine(const std::string& s, std::size_t maxLen = 200) {
  std::string out;
  for (char c : s) {
    if (out.size() >= maxLen) {
      out += "...";
      break;
    }
    out += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '?' : c;
  }
  return out;
}

[[noreturn]] void fail(const std::string& file, const std::string& where, const std::string& problem) {
  throwInputError(oneLine(file, 4096), where, oneLine(problem, 1000));
}

std::string lineWhere(std::size_t line) { return "line " + std::to_string(line); }

// Reads a regular file into memory; throws InputError naming the file on failure.
std::string readWholeFile(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) fail(path, "", std::string("cannot open: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) fail(path, "", "cannot open: is a directory");
  if (!S_ISREG(st.st_mode)) fail(path, "", "cannot open: not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "", std::string("cannot open: ") + std::strerror(errno));
  std::string text;
  char chunk[1 << 16];
  text.reserve(static_cast<std::size_t>(st.st_size));
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) text.append(chunk, static_cast<std::size_t>(in.gcount()));
  if (in.bad()) fail(path, "", "read error");
  return text;
}

// ---- Pre-scan ------------------------------------------------------------------------------

struct ObjScan {
  std::size_t vertices = 0, faces = 0, knownStatements = 0;
  std::size_t unknownStatements = 0, firstUnknownLine = 0;
  std::string firstUnknown;
  long maxPositiveIndex = 0;  // largest positive face index, checked against the final count
  std::size_t maxPositiveLine = 0;
};

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// Splits [p, end) into whitespace-separated tokens.
struct Tokens {
  const char* p;
  const char* end;
  bool next(const char*& b, const char*& e) {
    while (p < end && isSpace(*p)) ++p;
    if (p == end) return false;
    b = p;
    while (p < end && !isSpace(*p)) ++p;
    e = p;
    return true;
  }
};

bool isKnownStatement(const std::string& kw) {
  static const std::set<std::string> known = {
      "v",     "vn",   "vt",    "vp",   "f",       "l",        "p",       "g",      "o",
      "s",     "usemtl", "mtllib", "vw", "t",      "cstype",   "deg",     "bmat",   "step",
      "curv",  "curv2", "surf", "parm", "trim",    "hole",     "scrv",    "sp",     "end",
      "con",   "mg",   "ctech", "stech", "bevel",  "c_interp", "d_interp", "lod",   "maplib",
      "usemap", "shadow_obj", "trace_obj", "call", "csh"};
  return known.count(kw) > 0;
}

// First byte that cannot be in a text file (NUL or a control character other than whitespace).
// A control character other than \t \n \v \f \r (branch-free, so the block scan vectorizes).
unsigned char isBinaryByte(unsigned char u) {
  return static_cast<unsigned char>((u < 0x20) & (static_cast<unsigned char>(u - '\t') > '\r' - '\t'));
}

const char* findBinaryByte(const std::string& text) {
  const std::size_t block = 4096;
  const auto* bytes = reinterpret_cast<const unsigned char*>(text.data());
  for (std::size_t start = 0; start < text.size(); start += block) {
    std::size_t end = std::min(text.size(), start + block);
    unsigned char any = 0;
    for (std::size_t i = start; i < end; ++i) any |= isBinaryByte(bytes[i]);
    if (!any) continue;
    for (std::size_t i = start; i < end; ++i)
      if (isBinaryByte(static_cast<unsigned char>(text[i]))) return &text[i];
  }
  return nullptr;
}

void scanVertex(const std::string& file, std::size_t line, Tokens tok) {
  const char *b, *e;
  for (int i = 0; i < 3; ++i) {
    if (!tok.next(b, e)) fail(file, lineWhere(line), "vertex needs 3 coordinates");
    if (*b == '+') ++b;
    float value = 0.0f;
    auto r = std::from_chars(b, e, value);
    if (r.ec == std::errc::result_out_of_range)
      fail(file, lineWhere(line), "vertex coordinate '" + std::string(b, e) + "' out of float range");
    if (r.ec != std::errc() || r.ptr != e)
      fail(file, lineWhere(line), "bad vertex coordinate '" + std::string(b, e) + "'");
    if (!std::isfinite(value))
      fail(file, lineWhere(line), "vertex coordinate '" + std::string(b, e) + "' is not finite");
  }
}

// Parses one nonzero integer (an index of v/vt/vn) in [b, e).
bool parseIndex(const char* b, const char* e, long& index) {
  if (b < e && *b == '+') ++b;
  auto r = std::from_chars(b, e, index);
  return r.ec == std::errc() && r.ptr == e && index != 0;
}

void scanFace(const std::string& file, std::size_t line, Tokens tok, ObjScan& scan) {
  const char *b, *e;
  int corners = 0;
  while (tok.next(b, e)) {
    const char* slash = std::find(b, e, '/');
    long index = 0;
    if (!parseIndex(b, slash, index))
      fail(file, lineWhere(line), index == 0 && slash - b == 1 && *b == '0'
                                      ? "face index 0 is invalid (OBJ indices start at 1)"
                                      : "bad face vertex '" + std::string(b, e) + "'");
    for (const char* s = slash; s < e;) {  // optional vt / vn parts: empty or a nonzero integer
      const char* partEnd = std::find(s + 1, e, '/');
      long other = 0;
      if (partEnd > s + 1 && !parseIndex(s + 1, partEnd, other))
        fail(file, lineWhere(line), "bad face vertex '" + std::string(b, e) + "'");
      s = partEnd;
    }
    if (index < 0 && static_cast<long>(scan.vertices) + index < 0)
      fail(file, lineWhere(line),
           "face index " + std::to_string(index) + " out of range (" + std::to_string(scan.vertices) +
               " vertices before it)");
    if (index > scan.maxPositiveIndex) {
      scan.maxPositiveIndex = index;
      scan.maxPositiveLine = line;
    }
    ++corners;
  }
  if (corners < 3) fail(file, lineWhere(line), "face has fewer than 3 vertices");
  ++scan.faces;
}

void scanStatement(const std::string& file, std::size_t line, const char* b, const char* end,
                   ObjScan& scan) {
  Tokens tok{b, end};
  const char *kb, *ke;
  if (!tok.next(kb, ke) || *kb == '#') return;
  std::size_t len = static_cast<std::size_t>(ke - kb);
  if (len == 1 && *kb == 'v') {
    scanVertex(file, line, tok);
    ++scan.vertices;
  } else if (len == 1 && *kb == 'f') {
    scanFace(file, line, tok, scan);
  } else if (!isKnownStatement(std::string(kb, ke))) {
    if (scan.unknownStatements++ == 0) {
      scan.firstUnknownLine = line;
      scan.firstUnknown = oneLine(std::string(kb, ke), 40);
    }
    return;
  }
  ++scan.knownStatements;
}

ObjScan scanObjText(const std::string& file, const std::string& text) {
  if (const char* bad = findBinaryByte(text)) {
    std::size_t line = 1 + static_cast<std::size_t>(std::count(text.data(), bad, '\n'));
    fail(file, lineWhere(line), "not an OBJ file (binary data)");
  }
  ObjScan scan;
  const char* p = text.data();
  const char* end = p + text.size();
  for (std::size_t line = 1; p < end; ++line) {
    const char* eol = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
    if (!eol) eol = end;
    scanStatement(file, line, p, eol, scan);
    p = eol + 1;
  }
  if (scan.knownStatements == 0 && scan.unknownStatements > 0)
    fail(file, lineWhere(scan.firstUnknownLine),
         "not an OBJ file (unknown statement '" + scan.firstUnknown + "')");
  if (scan.maxPositiveIndex > static_cast<long>(scan.vertices))
    fail(file, lineWhere(scan.maxPositiveLine),
         "face index " + std::to_string(scan.maxPositiveIndex) + " out of range (" +
             std::to_string(scan.vertices) + " vertices)");
  if (scan.faces == 0) fail(file, "", "no triangles (the OBJ has no faces)");
  return scan;
}

// ---- tinyobjloader --------------------------------------------------------------------------

// Reads `mtllib` files relative to the OBJ's folder (tinyobj's own reader splits its search path
// at ':' and cannot take absolute names); remembers missing ones for a warning.
class MtlReader : public tinyobj::MaterialReader {
 public:
  explicit MtlReader(std::string dir) : dir_(std::move(dir)) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* matMap, std::string* warn, std::string* err) override {
    std::string path = (name.empty() || name[0] == '/' || dir_.empty()) ? name : dir_ + "/" + name;
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
    std::ifstream in(path);
    if (!in) {
      missing.push_back(path);
      return false;
    }
    found.push_back(path);
    tinyobj::LoadMtl(matMap, materials, &in, warn, err);
    return true;
  }
  std::vector<std::string> missing, found;
  std::string notRegular;  // "<path>': <why>" of the first mtllib that exists but is not a regular file

 private:
  std::string dir_;
};

// std::streambuf over a string, so tinyobj parses the text already read without a copy.
struct MemoryBuf : std::streambuf {
  explicit MemoryBuf(std::string& s) { setg(&s[0], &s[0], &s[0] + s.size()); }
};

struct ObjData {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::vector<std::string> mtlFiles;  // the MTL files read
};

std::string folderOf(const std::string& path) {
  std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return "";
  return slash == 0 ? "/" : path.substr(0, slash);
}

void addWarnings(const std::string& file, const std::string& text, std::vector<std::string>* warnings) {
  if (!warnings) return;
  std::set<std::string> seen;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty() || line == "." || !seen.insert(line).second) continue;
    if (seen.size() > 5) {
      warnings->push_back(oneLine(file) + ": more tinyobjloader warnings omitted");
      return;
    }
    warnings->push_back(oneLine(file) + ": " + oneLine(line));
  }
}

ObjData parseWithTinyObj(const std::string& file, std::string& text, std::vector<std::string>* warnings) {
  ObjData data;
  MemoryBuf buf(text);
  std::istream in(&buf);
  MtlReader mtl(folderOf(file));
  std::string warn, err;
  bool ok = tinyobj::LoadObj(&data.attrib, &data.shapes, &data.materials, &warn, &err, &in, &mtl,
                             /*triangulate=*/true, /*default_vcols_fallback=*/false);
  if (!mtl.notRegular.empty())
    fail(file, "mtllib", "cannot open '" + mtl.notRegular);
  if (!ok) fail(file, "", "cannot parse OBJ: " + err.substr(0, err.find('\n')));
  data.mtlFiles = mtl.found;
  if (warnings) {
    for (const std::string& m : mtl.missing)
      warnings->push_back(oneLine(file) + ": material file '" + oneLine(m) + "' not found, using default material");
  }
  // tinyobj's own missing-file lines duplicate the ones above; keep its other warnings.
  std::string rest;
  std::istringstream lines(warn + err);
  std::string line;
  while (std::getline(lines, line))
    if (line.find("Material file [") == std::string::npos && line.find("Failed to load material") == std::string::npos)
      rest += line + "\n";
  addWarnings(file, rest, warnings);
  return data;
}

// ---- Conversion -----------------------------------------------------------------------------

glm::vec3 toVec3(const tinyobj::real_t* c) {
  return glm::vec3(static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]));
}

bool validColor(const glm::vec3& c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && c.x >= 0 && c.y >= 0 &&
         c.z >= 0;
}

// Appends the OBJ's materials; returns the index of the first.
std::uint32_t appendMaterials(const std::string& file, const std::vector<tinyobj::material_t>& mats,
                              Scene& scene, std::vector<std::string>* warnings) {
  auto base = static_cast<std::uint32_t>(scene.materials.size());
  GlossyScaling scaled;
  for (const tinyobj::material_t& m : mats) {
    MaterialDesc d;
    d.name = m.name;
    d.albedo = toVec3(m.diffuse);
    d.emission = toVec3(m.emission);
    if (!validColor(d.albedo)) fail(file, "material '" + oneLine(m.name, 60) + "'", "Kd must be finite and >= 0");
    if (!validColor(d.emission)) fail(file, "material '" + oneLine(m.name, 60) + "'", "Ke must be finite and >= 0");
    d.specular = toVec3(m.specular);  // Ks, Ns: the glossy lobe (issue 12)
    d.specularExponent = m.shininess;
    scaled.note(oneLine(m.name, 60), checkGlossyMaterial(oneLine(file, 4096), "material '" + oneLine(m.name, 60) + "'", d));
    scene.materials.push_back(d);
  }
  scaled.warn(oneLine(file, 4096), warnings);
  return base;
}

bool isDegenerate(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  glm::vec3 n = glm::cross(b - a, c - a);
  bool finite = std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z);
  return !finite || (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f);
}

void extendBounds(Scene& scene, const SceneTriangle& t) {
  bool first = scene.triangles.empty();
  for (const glm::vec3& v : t.v) {
    scene.boundsMin = first ? v : glm::min(scene.boundsMin, v);
    scene.boundsMax = first ? v : glm::max(scene.boundsMax, v);
    first = false;
  }
}

std::size_t countFaces(const ObjData& data) {
  std::size_t n = 0;
  for (const auto& s : data.shapes) n += s.mesh.num_face_vertices.size();
  return n;
}

void appendTriangles(const std::string& file, const ObjData& data, std::uint32_t materialBase, Scene& scene) {
  const std::vector<tinyobj::real_t>& pos = data.attrib.vertices;
  const std::size_t vertexCount = pos.size() / 3;
  scene.triangles.reserve(scene.triangles.size() + countFaces(data));
  for (const tinyobj::shape_t& shape : data.shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    std::size_t offset = 0;
    for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      std::size_t corners = mesh.num_face_vertices[f];
      if (corners != 3) fail(file, "shape '" + oneLine(shape.name, 60) + "'", "face was not triangulated");
      SceneTriangle t{};
      for (int k = 0; k < 3; ++k) {
        int vi = mesh.indices[offset + k].vertex_index;
        if (vi < 0 || static_cast<std::size_t>(vi) >= vertexCount)
          fail(file, "", "face index " + std::to_string(vi + 1) + " out of range (" +
                             std::to_string(vertexCount) + " vertices)");
        t.v[k] = toVec3(&pos[3 * static_cast<std::size_t>(vi)]);
      }
      offset += corners;
      if (isDegenerate(t.v[0], t.v[1], t.v[2])) {
        ++scene.degenerateDropped;
        continue;
      }
      int mid = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
      bool hasMaterial = mid >= 0 && static_cast<std::size_t>(mid) < data.materials.size();
      t.material = hasMaterial ? materialBase + static_cast<std::uint32_t>(mid) : defaultMaterialIndex(scene);
      extendBounds(scene, t);
      scene.triangles.push_back(t);
    }
  }
}

}  // namespace

std::uint32_t defaultMaterialIndex(Scene& scene) {
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const MaterialDesc& m = scene.materials[i];
    if (m.name == kDefaultMaterialName && m.albedo == glm::vec3(0.5f) && m.emission == glm::vec3(0.0f))
      return static_cast<std::uint32_t>(i);
  }
  MaterialDesc d;
  d.name = kDefaultMaterialName;
  scene.materials.push_back(d);
  return static_cast<std::uint32_t>(scene.materials.size() - 1);
}

void loadObjInto(const std::string& objPath, Scene& scene, std::vector<std::string>* warnings) {
  std::string text = readWholeFile(objPath);
  if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);  // UTF-8 byte order mark
  ObjScan scan = scanObjText(objPath, text);
  if (warnings && scan.unknownStatements > 0)
    warnings->push_back(oneLine(objPath) + ": " + lineWhere(scan.firstUnknownLine) + ": unknown OBJ statement '" +
                        scan.firstUnknown + "' ignored" +
                        (scan.unknownStatements > 1
                             ? " (" + std::to_string(scan.unknownStatements - 1) + " more unknown statements)"
                             : std::string()));
  ObjData data = parseWithTinyObj(objPath, text, warnings);
  scene.inputFiles.push_back(objPath);
  scene.inputFiles.insert(scene.inputFiles.end(), data.mtlFiles.begin(), data.mtlFiles.end());
  std::size_t trianglesBefore = scene.triangles.size();
  std::size_t droppedBefore = scene.degenerateDropped;
  std::uint32_t materialBase = appendMaterials(objPath, data.materials, scene, warnings);
  appendTriangles(objPath, data, materialBase, scene);
  if (scene.triangles.size() == trianglesBefore)
    fail(objPath, "", "no triangles (" + std::to_string(scene.degenerateDropped - droppedBefore) +
                          " degenerate triangles dropped)");
}

}  // namespace montecl
