// mitsuba_xml.cpp: reads Mitsuba scene XML files into pugixml documents (mitsuba_xml.h): includes,
// defaults, ids, and the line and column of an element from pugixml's byte offsets.
#include "scene/mitsuba_xml.h"

#include <algorithm>
#include <cctype>

#include "scene/load_util.h"
#include "util/errors.h"

namespace montecl {
namespace {

// Nested <include>s deeper than this are a cycle (or a file nobody writes by hand).
constexpr int kMaxXmlIncludeDepth = 32;

}  // namespace

std::string MiLoc::str() const { return file + ":" + std::to_string(line) + ":" + std::to_string(column); }

void mitsubaFail(const MiLoc& loc, const std::string& problem) { throw InputError(oneLine(loc.str() + ": " + problem, 400)); }

std::string miSnakeCase(const std::string& name) {
  std::string out;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    if (std::isupper(c) && i > 0 && std::islower(static_cast<unsigned char>(name[i - 1]))) out += '_';
    out += char(std::tolower(c));
  }
  return out;
}

MiDocument::MiDocument(const std::string& mainPath, std::vector<std::string>& inputFiles) {
  const int f = load(mainPath, MiLoc{mainPath, 1, 1}, inputFiles);
  MiElem root{files_[std::size_t(f)].doc->document_element(), f};
  if (root.tag() != "scene") mitsubaFail(loc(root), "the root element is <" + oneLine(root.tag(), 40) + ">, not <scene>: not a Mitsuba scene file");
  // Mitsuba 0.x files say version="0.5.0" or "0.6.0" and spell properties in camelCase.
  const std::string version = root.node.attribute("version").value();
  camelCase_ = !version.empty() && version[0] == '0';
  collect(root, 0, inputFiles);
}

int MiDocument::load(const std::string& path, const MiLoc& from, std::vector<std::string>& inputFiles) {
  const std::string problem = fileProblem(path);
  if (!problem.empty()) mitsubaFail(from, "cannot open '" + oneLine(path, 160) + "': " + problem);
  File file;
  file.path = path;
  file.text = readWholeFile(path);
  file.lineStarts.push_back(0);
  for (std::size_t i = 0; i < file.text.size(); ++i)
    if (file.text[i] == '\n') file.lineStarts.push_back(i + 1);
  file.doc = std::make_unique<pugi::xml_document>();
  const pugi::xml_parse_result r =
      file.doc->load_buffer(file.text.data(), file.text.size(), pugi::parse_default, pugi::encoding_utf8);
  files_.push_back(std::move(file));
  inputFiles.push_back(path);
  const int index = int(files_.size()) - 1;
  if (!r) {
    // pugixml reports a byte offset: the line and column of that byte.
    MiElem at{pugi::xml_node(), index};
    MiLoc where = loc(at);
    const std::vector<std::size_t>& ls = files_.back().lineStarts;
    const std::size_t off = std::min<std::size_t>(std::size_t(std::max<std::ptrdiff_t>(r.offset, 0)), files_.back().text.size());
    const std::size_t line = std::size_t(std::upper_bound(ls.begin(), ls.end(), off) - ls.begin());
    where.line = int(line);
    where.column = int(off - ls[line - 1]) + 1;
    mitsubaFail(where, std::string("malformed XML: ") + r.description());
  }
  if (!files_.back().doc->document_element()) mitsubaFail(MiLoc{path, 1, 1}, "no element: not a Mitsuba scene file");
  registerIds(MiElem{files_.back().doc->document_element(), index});
  return index;
}

void MiDocument::registerIds(const MiElem& e) {
  const pugi::xml_attribute id = e.node.attribute("id");
  if (id && e.tag() != "ref") {
    auto [it, fresh] = ids_.emplace(id.value(), e);
    if (!fresh) mitsubaFail(loc(e), "id '" + oneLine(id.value(), 60) + "' is used twice (first at " + loc(it->second).str() + ")");
  }
  for (const MiElem& c : children(e)) registerIds(c);
}

void MiDocument::collect(const MiElem& scene, int depth, std::vector<std::string>& inputFiles) {
  for (const MiElem& c : children(scene)) {
    if (c.tag() == "default") {
      const std::string name = c.node.attribute("name").value();
      if (name.empty() || !c.node.attribute("value")) mitsubaFail(loc(c), "<default> needs 'name' and 'value'");
      defaults_.emplace(name, c.node.attribute("value").value());  // the first definition holds
    } else if (c.tag() == "include") {
      if (depth >= kMaxXmlIncludeDepth) mitsubaFail(loc(c), "<include> nested more than 32 deep (does a file include itself?)");
      const std::string name = attr(c, "filename");
      if (name.empty()) mitsubaFail(loc(c), "<include> needs a 'filename'");
      const int f = load(resolve(name), loc(c), inputFiles);
      MiElem root{files_[std::size_t(f)].doc->document_element(), f};
      if (root.tag() != "scene") mitsubaFail(loc(root), "an included file's root must be <scene>, not <" + oneLine(root.tag(), 40) + ">");
      collect(root, depth + 1, inputFiles);
    } else {
      children_.push_back(c);
    }
  }
}

std::vector<MiElem> MiDocument::children(const MiElem& e) const {
  std::vector<MiElem> out;
  for (pugi::xml_node n = e.node.first_child(); n; n = n.next_sibling())
    if (n.type() == pugi::node_element) out.push_back(MiElem{n, e.file});
  return out;
}

MiLoc MiDocument::loc(const MiElem& e) const {
  const File& f = files_[std::size_t(e.file)];
  MiLoc l{f.path, 1, 1};
  const std::ptrdiff_t off = e.node ? e.node.offset_debug() : -1;
  if (off < 0) return l;
  // offset_debug points at the element's name, one past its '<'.
  const std::size_t at = std::size_t(off) > 0 ? std::size_t(off) - 1 : 0;
  const std::size_t line = std::size_t(std::upper_bound(f.lineStarts.begin(), f.lineStarts.end(), at) - f.lineStarts.begin());
  l.line = int(line);
  l.column = int(at - f.lineStarts[line - 1]) + 1;
  return l;
}

std::string MiDocument::attr(const MiElem& e, const char* name) const {
  const std::string raw = e.node.attribute(name).value();
  std::string out;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != '$') {
      out += raw[i];
      continue;
    }
    std::size_t j = i + 1;
    while (j < raw.size() && (std::isalnum(static_cast<unsigned char>(raw[j])) || raw[j] == '_')) ++j;
    const std::string key = raw.substr(i + 1, j - i - 1);
    if (key.empty()) mitsubaFail(loc(e), std::string("attribute '") + name + "': '$' without a name");
    auto it = defaults_.find(key);
    if (it == defaults_.end()) mitsubaFail(loc(e), "'$" + oneLine(key, 40) + "' is not defined (no <default name=\"" + oneLine(key, 40) + "\" value=...>)");
    out += it->second;
    i = j - 1;
  }
  return out;
}

MiElem MiDocument::byId(const std::string& id) const {
  auto it = ids_.find(id);
  return it == ids_.end() ? MiElem{} : it->second;
}

std::string MiDocument::resolve(const std::string& name) const { return besideFile(mainPath(), name); }

}  // namespace montecl
