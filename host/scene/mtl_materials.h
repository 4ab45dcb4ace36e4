// mtl_materials.h: the MTL side of the OBJ loader. MtlReader opens the `mtllib` files for
// tinyobjloader (relative to the OBJ, regular files only) and scans each one's text for the line
// of every statement; appendMtlMaterials() turns tinyobj's materials into MaterialDesc (Kd, Ke,
// Ks, Ns, map_Kd, map_d, map_Ke, norm, bump with paths resolved beside the MTL), validates them (InputError
// "<mtl>: line N: material 'm': <problem>") and warns once per kind of statement montecl does
// not use (Ka, illum, Ni, map_Ks, d/Tr as a constant, texture options, ...).
#pragma once
#include <tiny_obj_loader.h>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "scene/load_util.h"
#include "scene/scene.h"

namespace montecl {

// One `newmtl` block of an MTL's text: the first line of each statement in it.
struct MtlBlock {
  std::map<std::string, std::size_t> line;  // statement keyword -> line number
  // norm / bump keyword -> the text after its -bm (first line): tinyobjloader reads a word that is
  // not a number as 1, so the loader checks the text itself.
  std::map<std::string, std::string> bm;
};

struct MtlFile {
  std::string path;                 // as opened
  std::size_t firstMaterial = 0;    // tinyobj materials [firstMaterial, firstMaterial + count)
  std::size_t count = 0;
  std::vector<MtlBlock> blocks;     // in tinyobj's order (used when the counts agree)
  KindWarnings unused{""};          // statements montecl does not use, one warning per kind
};

class MtlReader : public tinyobj::MaterialReader {
 public:
  explicit MtlReader(std::string objPath) : objPath_(std::move(objPath)) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* matMap, std::string* warn, std::string* err) override;
  std::vector<std::string> missing;  // mtllib paths that do not exist
  std::vector<MtlFile> files;        // the MTL files read
  std::string notRegular;  // "<path>': <why>" of the first mtllib that exists but is not a regular file

 private:
  std::string objPath_;
};

// Appends the materials (one per tinyobj material, in order) to scene; returns the index of the
// first. Texture files are checked to exist and added to scene.inputFiles.
std::uint32_t appendMtlMaterials(const std::string& objPath, const std::vector<tinyobj::material_t>& mats,
                                 const std::vector<MtlFile>& files, Scene& scene,
                                 std::vector<std::string>* warnings);

}  // namespace montecl
