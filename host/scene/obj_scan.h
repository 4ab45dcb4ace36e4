// obj_scan.h: a fast pre-scan of OBJ text that catches what tinyobjloader silently accepts
// (binary data, non-OBJ text, NaN/inf numbers in v/vt/vn, out-of-range face indices; vt/vn
// indices out of range are counted for a warning) and
// reports it as InputError "<obj>: line N: <problem>".
#pragma once
#include <cstddef>
#include <string>

namespace montecl {

struct ObjScan {
  std::size_t faces = 0, knownStatements = 0;
  std::size_t unknownStatements = 0, firstUnknownLine = 0;
  std::string firstUnknown;
  std::size_t count[3] = {0, 0, 0};  // v, vt, vn statements
  std::size_t badAttributeIndices = 0;  // vt/vn indices out of range (those faces lose them)
  std::string firstBadAttribute;        // "line N: <problem>" of the first
};

// Throws InputError for text that is not a usable OBJ (see above, and: no faces at all).
ObjScan scanObjText(const std::string& file, const std::string& text);

}  // namespace montecl
