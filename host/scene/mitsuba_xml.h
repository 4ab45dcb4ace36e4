// mitsuba_xml.h: a Mitsuba 3 scene file as XML elements with their places: reads the main file and
// its <include>d files through pugixml, substitutes $name by <default> values, maps every id to
// its element, and gives each element's file:line:column. Writes nothing; errors are one line.
#pragma once
#include <pugixml.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace montecl {

struct MiLoc {
  std::string file;
  int line = 0, column = 0;
  std::string str() const;  // "<file>:<line>:<column>"
};

// Throws InputError "<file>:<line>:<column>: <problem>" (one line).
[[noreturn]] void mitsubaFail(const MiLoc& loc, const std::string& problem);

// An element of one of the files read.
struct MiElem {
  pugi::xml_node node;
  int file = -1;
  explicit operator bool() const { return bool(node); }
  std::string tag() const { return node.name(); }
};

class MiDocument {
 public:
  // Reads the main file (bad XML, a root other than <scene>: mitsubaFail). Every file read is
  // appended to inputFiles.
  MiDocument(const std::string& mainPath, std::vector<std::string>& inputFiles);

  const std::string& mainPath() const { return files_[0].path; }
  // The scene's children in order, each <include> replaced by the included scene's children and
  // the <default> elements left out (they were read first).
  const std::vector<MiElem>& sceneChildren() const { return children_; }
  std::vector<MiElem> children(const MiElem& e) const;  // element children, in order
  MiLoc loc(const MiElem& e) const;
  // An attribute's value with every $name replaced (an undefined name: mitsubaFail); "" when absent.
  std::string attr(const MiElem& e, const char* name) const;
  bool hasAttr(const MiElem& e, const char* name) const { return bool(e.node.attribute(name)); }
  // The element whose id is `id` (anywhere in the files), or an empty MiElem.
  MiElem byId(const std::string& id) const;
  // Files of format version 0.x (Mitsuba 0.5 / 0.6) name properties in camelCase ("sampleCount"),
  // Mitsuba 3 in snake_case; property names are read in Mitsuba 3's spelling.
  bool camelCase() const { return camelCase_; }
  // A file name as given in the scene, resolved against the main file's folder (as Mitsuba's file
  // resolver does).
  std::string resolve(const std::string& name) const;

 private:
  struct File {
    std::string path, text;
    std::vector<std::size_t> lineStarts;
    std::unique_ptr<pugi::xml_document> doc;
  };
  int load(const std::string& path, const MiLoc& from, std::vector<std::string>& inputFiles);
  void collect(const MiElem& scene, int depth, std::vector<std::string>& inputFiles);
  void registerIds(const MiElem& e);
  std::vector<File> files_;
  std::vector<MiElem> children_;
  std::map<std::string, std::string> defaults_;
  std::map<std::string, MiElem> ids_;
  bool camelCase_ = false;
};

// A property name in Mitsuba 3's spelling: "sampleCount" -> "sample_count", "intIOR" -> "int_ior".
std::string miSnakeCase(const std::string& name);

}  // namespace montecl
