// ply_reader.h: a PLY reader (ASCII, binary little and big endian) for the mesh loader
// (ply_mesh.cpp). It parses the header, then walks every element's rows and hands the values of
// the properties the caller asked for to it, skipping the others. Written for montecl rather than
// taken from Assimp (Debian's 5.2.5 reads `tristrips` as a single face and mis-reads some
// big-endian files: assimp issues #6296, #2337). Every problem is an InputError
// "<file>: <header line N | element 'e' row R | byte B>: <problem>".
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace montecl {

enum class PlyType : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // the value type (the item type of a list)
  bool isList = false;
  PlyType countType = PlyType::UInt8;  // the list's length type
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t dataOffset = 0;  // first byte after "end_header\n"
};

// Parses the header of text (the whole file); throws InputError naming file and header line.
PlyHeader parsePlyHeader(const std::string& file, const std::string& text);

// Receives one row's values: scalar properties in `scalars` (by property index, lists as NaN) and
// lists in `lists` (by property index, empty for scalars). Values are doubles (exact for every
// PLY type). Called once per row of each element, in file order.
struct PlyRow {
  const PlyElement* element = nullptr;
  std::uint64_t row = 0;
  std::vector<double> scalars;
  std::vector<std::vector<double>> lists;
};
using PlyRowSink = std::function<void(const PlyRow&)>;

// A PLY value as the file means it, for messages: "3", "1.5", "1e-07", "nan" (std::to_string
// would print 1e-07 as 0.000000, and a cast to an integer type is undefined for NaN or 1e30).
std::string plyNumber(double v);

// Reads every element's rows after the header; `wanted(element)` says whose rows go to sink
// (the others are parsed and skipped). Throws InputError for truncated or malformed data.
void readPlyData(const std::string& file, const std::string& text, const PlyHeader& header,
                 const std::function<bool(const PlyElement&)>& wanted, const PlyRowSink& sink);

}  // namespace montecl
