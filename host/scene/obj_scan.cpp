// obj_scan.cpp: the OBJ pre-scan (obj_scan.h): one pass over the text, line by line; checks
// numbers of v/vt/vn statements and the v/vt/vn indices of faces.
#include "scene/obj_scan.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <set>

#include "scene/load_util.h"

namespace montecl {
namespace {

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

const char* const kKindName[3] = {"vertex", "texture", "normal"};
const char* const kKeyword[3] = {"v", "vt", "vn"};

// v: 3 numbers needed; vt: 1 to 3; vn: 3. What follows those is left to tinyobjloader (v's w or
// colour, a vt's non-numeric tail).
void scanNumbers(const std::string& file, std::size_t line, Tokens tok, int kind) {
  const int needed = kind == 1 ? 1 : 3;
  for (int i = 0; i < 3; ++i) {
    const char *b, *e;
    if (!tok.next(b, e)) {
      if (i >= needed) return;
      loadFail(file, lineWhere(line), std::string(kKeyword[kind]) + " needs " + (kind == 1 ? "1 to 3" : "3") +
                                          " numbers");
    }
    if (*b == '+') ++b;
    float value = 0.0f;
    auto r = std::from_chars(b, e, value);
    const std::string what = std::string(kKindName[kind]) + " coordinate '" + std::string(b, e) + "'";
    if (r.ec == std::errc::result_out_of_range) loadFail(file, lineWhere(line), what + " out of float range");
    if (r.ec != std::errc() || r.ptr != e) {
      if (i >= needed) return;
      loadFail(file, lineWhere(line), "bad " + what);
    }
    if (!std::isfinite(value)) loadFail(file, lineWhere(line), what + " is not finite");
  }
}

// Parses one nonzero integer (an index of v/vt/vn) in [b, e).
bool parseIndex(const char* b, const char* e, long& index) {
  if (b < e && *b == '+') ++b;
  auto r = std::from_chars(b, e, index);
  return r.ec == std::errc() && r.ptr == e && index != 0;
}

// A vt/vn index out of range: the face gets no texture coordinates / normals (a warning), as
// tinyobjloader leaves them out.
void noteBadAttribute(ObjScan& scan, std::size_t line, const std::string& problem) {
  if (scan.badAttributeIndices++ == 0) scan.firstBadAttribute = lineWhere(line) + ": " + problem;
}

struct MaxIndex {
  long value = 0;
  std::size_t line = 0;
};

void scanFace(const std::string& file, std::size_t line, Tokens tok, ObjScan& scan, MaxIndex* maxIndex) {
  const char *b, *e;
  int corners = 0;
  while (tok.next(b, e)) {
    const std::string corner(b, e);
    const char* partBegin = b;
    for (int part = 0; part < 3 && partBegin <= e; ++part) {
      const char* partEnd = std::find(partBegin, e, '/');
      if (part > 0 && partEnd == partBegin) {  // empty vt (v//vn) or trailing slash
        if (partEnd == e) break;
        partBegin = partEnd + 1;
        continue;
      }
      long index = 0;
      if (!parseIndex(partBegin, partEnd, index))
        loadFail(file, lineWhere(line), index == 0 && partEnd - partBegin == 1 && *partBegin == '0'
                                            ? "face index 0 is invalid (OBJ indices start at 1)"
                                            : "bad face vertex '" + corner + "'");
      const long have = static_cast<long>(scan.count[part]);
      if (index < 0 && have + index < 0) {
        const std::string problem = std::string("face ") + (part == 0 ? "" : std::string(kKeyword[part]) + " ") +
                                    "index " + std::to_string(index) + " out of range (" + std::to_string(have) + " " +
                                    (part == 0 ? "vertices" : kKeyword[part]) + " before it)";
        if (part == 0) loadFail(file, lineWhere(line), problem);
        noteBadAttribute(scan, line, problem);
      }
      if (index > maxIndex[part].value) maxIndex[part] = {index, line};
      partBegin = partEnd + 1;
      if (partEnd == e) break;
      if (part == 2) loadFail(file, lineWhere(line), "bad face vertex '" + corner + "'");
    }
    ++corners;
  }
  if (corners < 3) loadFail(file, lineWhere(line), "face has fewer than 3 vertices");
  ++scan.faces;
}

void scanStatement(const std::string& file, std::size_t line, const char* b, const char* end, ObjScan& scan,
                   MaxIndex* maxIndex) {
  Tokens tok{b, end};
  const char *kb, *ke;
  if (!tok.next(kb, ke) || *kb == '#') return;
  const std::string kw(kb, ke);
  int kind = kw == "v" ? 0 : kw == "vt" ? 1 : kw == "vn" ? 2 : -1;
  if (kind >= 0) {
    scanNumbers(file, line, tok, kind);
    ++scan.count[kind];
  } else if (kw == "f") {
    scanFace(file, line, tok, scan, maxIndex);
  } else if (!isKnownStatement(kw)) {
    if (scan.unknownStatements++ == 0) {
      scan.firstUnknownLine = line;
      scan.firstUnknown = oneLine(kw, 40);
    }
    return;
  }
  ++scan.knownStatements;
}

}  // namespace

ObjScan scanObjText(const std::string& file, const std::string& text) {
  if (const char* bad = findBinaryByte(text)) {
    std::size_t line = 1 + static_cast<std::size_t>(std::count(text.data(), bad, '\n'));
    loadFail(file, lineWhere(line), "not an OBJ file (binary data)");
  }
  ObjScan scan;
  MaxIndex maxIndex[3];
  const char* p = text.data();
  const char* end = p + text.size();
  for (std::size_t line = 1; p < end; ++line) {
    const char* eol = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
    if (!eol) eol = end;
    scanStatement(file, line, p, eol, scan, maxIndex);
    p = eol + 1;
  }
  if (scan.knownStatements == 0 && scan.unknownStatements > 0)
    loadFail(file, lineWhere(scan.firstUnknownLine), "not an OBJ file (unknown statement '" + scan.firstUnknown + "')");
  for (int k = 0; k < 3; ++k)
    if (maxIndex[k].value > static_cast<long>(scan.count[k])) {
      const std::string problem = std::string("face ") + (k == 0 ? "" : std::string(kKeyword[k]) + " ") + "index " +
                                  std::to_string(maxIndex[k].value) + " out of range (" + std::to_string(scan.count[k]) +
                                  " " + (k == 0 ? "vertices" : kKeyword[k]) + ")";
      if (k == 0) loadFail(file, lineWhere(maxIndex[k].line), problem);
      noteBadAttribute(scan, maxIndex[k].line, problem);
    }
  if (scan.faces == 0) loadFail(file, "", "no triangles (the OBJ has no faces)");
  return scan;
}

}  // namespace montecl
