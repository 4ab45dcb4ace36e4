// ply_reader.cpp: PLY header and data (see ply_reader.h). Element counts and list lengths are
// checked against the bytes left before anything is allocated, so a corrupt count is an error,
// not an allocation of gigabytes.
#include "scene/ply_reader.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>

#include "scene/load_util.h"

namespace montecl {
namespace {

bool typeNamed(const std::string& name, PlyType& type) {
  static const std::map<std::string, PlyType> types = {
      {"char", PlyType::Int8},       {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},     {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},   {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},     {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},   {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  auto it = types.find(name);
  if (it == types.end()) return false;
  type = it->second;
  return true;
}

std::size_t typeSize(PlyType t) {
  switch (t) {
    case PlyType::Int8: case PlyType::UInt8: return 1;
    case PlyType::Int16: case PlyType::UInt16: return 2;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 1;
}

bool isIntegral(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  std::string w;
  while (in >> w) out.push_back(w);
  return out;
}

std::string rowWhere(const PlyElement& e, std::uint64_t row) {
  return "element '" + oneLine(e.name, 40) + "' row " + std::to_string(row);
}

// ---- Data cursors ---------------------------------------------------------------------------

struct Cursor {
  const std::string& file;
  const std::string& text;
  std::size_t pos;
  PlyFormat format;
  const PlyElement* element = nullptr;
  std::uint64_t row = 0;

  [[noreturn]] void fail(const std::string& problem) const { loadFail(file, rowWhere(*element, row), problem); }
  std::size_t left() const { return text.size() - pos; }

  double binary(PlyType t) {
    const std::size_t n = typeSize(t);
    if (left() < n) fail("truncated data (the file ends inside this row)");
    unsigned char b[8];
    std::memcpy(b, text.data() + pos, n);
    pos += n;
    const bool swap = format == PlyFormat::BinaryBigEndian;  // the host is little endian
    if (swap)
      for (std::size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    switch (t) {
      case PlyType::Int8: { std::int8_t v; std::memcpy(&v, b, 1); return v; }
      case PlyType::UInt8: return b[0];
      case PlyType::Int16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::UInt16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::Int32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::UInt32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::Float32: { float v; std::memcpy(&v, b, 4); return v; }
      case PlyType::Float64: { double v; std::memcpy(&v, b, 8); return v; }
    }
    return 0.0;
  }

  double ascii(PlyType t) {
    while (pos < text.size() && std::isspace(static_cast<unsigned char>(text[pos]))) ++pos;
    if (pos == text.size()) fail("truncated data (the file ends inside this row)");
    std::size_t end = pos;
    while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
    const char* b = text.data() + pos;
    const char* e = text.data() + end;
    if (*b == '+') ++b;
    double v = 0.0;
    auto r = std::from_chars(b, e, v);
    if (r.ec != std::errc() || r.ptr != e)
      fail("bad number '" + oneLine(std::string(text.data() + pos, std::min<std::size_t>(end - pos, 40))) + "'");
    pos = end;
    if (isIntegral(t) && v != std::floor(v)) fail("expected an integer, got " + plyNumber(v));
    return v;
  }

  double value(PlyType t) { return format == PlyFormat::Ascii ? ascii(t) : binary(t); }
};

// The fewest bytes one row of e can take (binary: exact for scalars; lists at least their length).
std::size_t minRowBytes(const PlyElement& e, PlyFormat f) {
  std::size_t n = 0;
  for (const PlyProperty& p : e.properties)
    n += f == PlyFormat::Ascii ? 2 : typeSize(p.isList ? p.countType : p.type);
  return n;
}

}  // namespace

PlyHeader parsePlyHeader(const std::string& file, const std::string& text) {
  PlyHeader h;
  if (text.compare(0, 3, "ply") != 0 || (text.size() > 3 && text[3] != '\n' && text[3] != '\r'))
    loadFail(file, "line 1", "not a PLY file (it does not start with 'ply')");
  std::size_t pos = 0, line = 0;
  bool sawFormat = false;
  for (;;) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) loadFail(file, "header", "no 'end_header' line");
    std::string s = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line;
    if (!s.empty() && s.back() == '\r') s.pop_back();
    const std::string where = "header line " + std::to_string(line);
    for (char c : s)
      if (static_cast<unsigned char>(c) < 0x20 && c != '\t') loadFail(file, where, "binary data in the header");
    const std::vector<std::string> w = words(s);
    if (line == 1) continue;  // "ply"
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") break;
    if (w[0] == "format") {
      if (w.size() != 3) loadFail(file, where, "expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
      if (w[1] == "ascii") h.format = PlyFormat::Ascii;
      else if (w[1] == "binary_little_endian") h.format = PlyFormat::BinaryLittleEndian;
      else if (w[1] == "binary_big_endian") h.format = PlyFormat::BinaryBigEndian;
      else loadFail(file, where, "unknown format '" + oneLine(w[1], 40) + "'");
      if (w[2] != "1.0" && w[2] != "1") loadFail(file, where, "unsupported PLY version '" + oneLine(w[2], 20) + "'");
      sawFormat = true;
    } else if (w[0] == "element") {
      if (w.size() != 3) loadFail(file, where, "expected 'element <name> <count>'");
      PlyElement e;
      e.name = w[1];
      auto r = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (r.ec != std::errc() || r.ptr != w[2].data() + w[2].size())
        loadFail(file, where, "bad element count '" + oneLine(w[2], 40) + "'");
      h.elements.push_back(e);
    } else if (w[0] == "property") {
      if (h.elements.empty()) loadFail(file, where, "property before any element");
      PlyProperty p;
      const bool list = w.size() >= 2 && w[1] == "list";
      if (list ? w.size() != 5 : w.size() != 3)
        loadFail(file, where, "expected 'property <type> <name>' or 'property list <count type> <type> <name>'");
      p.isList = list;
      p.name = w.back();
      if (!typeNamed(w[list ? 3 : 1], p.type)) loadFail(file, where, "unknown type '" + oneLine(w[list ? 3 : 1], 40) + "'");
      if (list && (!typeNamed(w[2], p.countType) || !isIntegral(p.countType)))
        loadFail(file, where, "list length type must be an integer type, got '" + oneLine(w[2], 40) + "'");
      h.elements.back().properties.push_back(p);
    } else {
      loadFail(file, where, "unknown header keyword '" + oneLine(w[0], 40) + "'");
    }
  }
  if (!sawFormat) loadFail(file, "header", "no 'format' line");
  for (const PlyElement& e : h.elements)
    if (e.properties.empty() && e.count > 0) loadFail(file, "header", "element '" + oneLine(e.name, 40) + "' has no properties");
  h.dataOffset = pos;
  return h;
}

void readPlyData(const std::string& file, const std::string& text, const PlyHeader& header,
                 const std::function<bool(const PlyElement&)>& wanted, const PlyRowSink& sink) {
  Cursor c{file, text, header.dataOffset, header.format};
  PlyRow row;
  for (const PlyElement& e : header.elements) {
    c.element = &e;
    c.row = 0;
    const std::size_t minBytes = minRowBytes(e, header.format);
    if (minBytes > 0 && e.count > c.left() / minBytes)
      loadFail(file, "element '" + oneLine(e.name, 40) + "'",
               std::to_string(e.count) + " rows cannot fit in the " + std::to_string(c.left()) + " bytes left");
    const bool keep = wanted(e);
    row.element = &e;
    row.scalars.assign(e.properties.size(), std::numeric_limits<double>::quiet_NaN());
    row.lists.assign(e.properties.size(), {});
    for (std::uint64_t r = 0; r < e.count; ++r) {
      c.row = r;
      row.row = r;
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& p = e.properties[k];
        if (!p.isList) {
          row.scalars[k] = c.value(p.type);
          continue;
        }
        const double n = c.value(p.countType);
        if (n < 0) c.fail("negative list length " + plyNumber(n));
        const std::size_t itemBytes = header.format == PlyFormat::Ascii ? 2 : typeSize(p.type);
        if (n > static_cast<double>(c.left() / itemBytes + 1))
          c.fail("list length " + plyNumber(n) + " longer than the data left");
        std::vector<double>& list = row.lists[k];
        list.resize(static_cast<std::size_t>(n));
        for (double& v : list) v = c.value(p.type);
      }
      if (keep) sink(row);
    }
  }
  if (header.format == PlyFormat::Ascii) {
    while (c.pos < text.size() && std::isspace(static_cast<unsigned char>(text[c.pos]))) ++c.pos;
    if (c.pos < text.size()) loadFail(file, "end of data", "unexpected data after the last element");
  }
}

std::string plyNumber(double v) {
  char buf[40];
  if (v == std::floor(v) && std::fabs(v) < 1e18) std::snprintf(buf, sizeof buf, "%.0f", v);  // integers exactly
  else std::snprintf(buf, sizeof buf, "%.9g", v);  // enough digits to tell any two floats apart
  return buf;
}

}  // namespace montecl
