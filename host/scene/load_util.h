// load_util.h: helpers shared by the mesh loaders (OBJ/MTL, PLY, glTF) and the scene file: one-line
// messages, reading a regular file, paths relative to a file, appending a triangle (degenerate ones
// counted, bounds grown), and warnings collected once per kind.
#pragma once
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace montecl {

// Replaces control characters so that a message stays on one line; cuts it at maxLen.
std::string oneLine(const std::string& s, std::size_t maxLen = 200);

// Throws InputError "<file>: <where>: <problem>" (each made one line).
[[noreturn]] void loadFail(const std::string& file, const std::string& where, const std::string& problem);

std::string lineWhere(std::size_t line);  // "line N"

// Empty when path is a readable regular file, else why not ("No such file or directory", ...).
std::string fileProblem(const std::string& path);

// The readable regular file whose path equals `path` but for the case of letters in the names of
// its folders and itself (what an exporter on a case-insensitive file system wrote, e.g. MTL's
// 'SP_LUK.JPG' for sp_luk.JPG); the first in name order where several match; "" when none does.
std::string findIgnoringCase(const std::string& path);

// Reads a regular file into memory; throws InputError naming the file on failure.
std::string readWholeFile(const std::string& path);

// The deepest nesting of arrays and objects a JSON text (scene file, glTF) may have: deeper ones
// are refused before parsing (tinygltf converts JSON values recursively: 15,000 nested arrays
// overflow the stack).
constexpr int kMaxJsonDepth = 512;

// Throws InputError "<file>: line N: nesting deeper than 512 arrays/objects" when the JSON text
// [text, text + size) nests deeper than kMaxJsonDepth (brackets inside strings do not count).
void checkJsonDepth(const std::string& file, const char* text, std::size_t size);

// The folder of a path ("" for a bare name).
std::string folderOf(const std::string& path);

// name as opened from the folder of baseFile (name itself when absolute or baseFile has no folder).
std::string besideFile(const std::string& baseFile, const std::string& name);

// Lower-case extension with the dot (".obj"), "" when none.
std::string lowerExtension(const std::string& path);

// Appends t unless it has zero (or non-finite) area, which is counted in scene.degenerateDropped
// instead; grows the scene bounds. Returns whether it was appended.
bool appendTriangle(Scene& scene, const SceneTriangle& t);

// Missing textures [from, end) of scene as one listing: "<file>: <where>: <lead>; also missing:
// <brief>, ... (N textures missing)" ("" when none).
std::string missingTexturesText(const Scene& scene, std::size_t from);

// Appends m to list unless the same texture reference (file, where) is there already (a mesh file
// used by two entries is read twice).
void noteMissingTexture(std::vector<MissingTexture>& list, MissingTexture m);

// A loader's texture that cannot be opened: recorded in scene.missingTextures (its material then
// goes without it). The loader calls failOnMissingTextures at the end of its file: with
// render.missing_textures error (the default) that throws the listing of the file's ones as one
// InputError, unless scene.deferMissingTextures (loadScene then reports the whole scene's).
void failOnMissingTextures(const Scene& scene, std::size_t from);
// The error for the missing textures from `from` on: their listing and the option that renders
// without them (--missing-textures warn).
std::string missingTexturesError(const Scene& scene, std::size_t from);

// Warnings collected by kind: the first occurrence of each kind is reported, with the number of
// further ones, when flushed: "<file>: <where>: <text> (N more like it; -v lists them)"; after
// listEveryWarning(true) (render -v) every occurrence is its own line.
void listEveryWarning(bool all);
class KindWarnings {
 public:
  explicit KindWarnings(std::string file) : file_(std::move(file)) {}
  void add(const std::string& kind, const std::string& where, const std::string& text);
  void flush(std::vector<std::string>* out) const;  // appends one line per kind (in first-seen order)
  bool empty() const { return kinds_.empty(); }

 private:
  struct Entry {
    std::string where, text;
    std::size_t more = 0, order = 0;
    std::vector<std::string> others;  // "<where>: <text>" of the further ones (the first kOthersKept)
  };
  std::string file_;
  std::map<std::string, Entry> kinds_;
};

}  // namespace montecl
