// load_util.cpp: helpers shared by the loaders (see load_util.h).
#include "scene/load_util.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#include "util/errors.h"

namespace montecl {

std::string oneLine(const std::string& s, std::size_t maxLen) {
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

void loadFail(const std::string& file, const std::string& where, const std::string& problem) {
  throwInputError(oneLine(file, 4096), oneLine(where, 200), oneLine(problem, 1000));
}

std::string missingTexturesText(const Scene& scene, std::size_t from) {
  const std::vector<MissingTexture>& list = scene.missingTextures;
  if (from >= list.size()) return "";
  const MissingTexture& first = list[from];
  std::string all = oneLine(first.file, 4096) + (first.where.empty() ? "" : ": " + first.where) + ": " + first.lead;
  if (list.size() - from > 1) {
    all += "; also missing:";
    for (std::size_t i = from + 1; i < list.size(); ++i)
      all += std::string(i > from + 1 ? ", " : " ") + (list[i].file == first.file ? "" : list[i].file + " ") + list[i].brief;
    all += " (" + std::to_string(list.size() - from) + " textures missing)";
  }
  return all;
}

void noteMissingTexture(std::vector<MissingTexture>& list, MissingTexture m) {
  for (const MissingTexture& x : list)
    if (x.file == m.file && x.where == m.where && x.lead == m.lead) return;
  list.push_back(std::move(m));
}

void failOnMissingTextures(const Scene& scene, std::size_t from) {
  if (scene.deferMissingTextures || scene.render.missingTextures != MissingTextures::Error ||
      from >= scene.missingTextures.size())
    return;
  throw InputError(missingTexturesError(scene, from));
}

std::string missingTexturesError(const Scene& scene, std::size_t from) {
  return oneLine(missingTexturesText(scene, from), 4096) + "; --missing-textures warn renders without them";
}

std::string lineWhere(std::size_t line) { return "line " + std::to_string(line); }

std::string fileProblem(const std::string& path) {
  struct stat st {};
  if (path.empty()) return "empty file name";
  if (::stat(path.c_str(), &st) != 0) return std::strerror(errno);
  if (S_ISDIR(st.st_mode)) return "is a directory";
  if (!S_ISREG(st.st_mode)) return "not a regular file";
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::strerror(errno);
  return "";
}

namespace {

std::string lowered(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The entries of folder whose names equal name but for case, in name order.
std::vector<std::filesystem::path> sameNameIgnoringCase(const std::filesystem::path& folder, const std::string& name) {
  std::vector<std::filesystem::path> found;
  std::error_code ec;
  const std::string want = lowered(name);
  for (std::filesystem::directory_iterator it(folder.empty() ? "." : folder, ec), end; !ec && it != end; it.increment(ec))
    if (lowered(it->path().filename().string()) == want) found.push_back(folder / it->path().filename());
  std::sort(found.begin(), found.end());
  return found;
}

// Every existing path that matches the components of p but for case (folders only while dirs).
std::vector<std::filesystem::path> matchesIgnoringCase(const std::filesystem::path& p) {
  std::error_code ec;
  if (std::filesystem::exists(p, ec)) return {p};
  const std::filesystem::path parent = p.parent_path();
  if (p.filename().empty() || parent == p) return {};
  std::vector<std::filesystem::path> parents = parent.empty() ? std::vector<std::filesystem::path>{""} : matchesIgnoringCase(parent);
  std::vector<std::filesystem::path> out;
  for (const std::filesystem::path& folder : parents) {
    if (!folder.empty() && !std::filesystem::is_directory(folder, ec)) continue;
    for (const std::filesystem::path& f : sameNameIgnoringCase(folder, p.filename().string())) out.push_back(f);
  }
  return out;
}

}  // namespace

std::string findIgnoringCase(const std::string& path) {
  for (const std::filesystem::path& f : matchesIgnoringCase(std::filesystem::path(path).lexically_normal()))
    if (fileProblem(f.string()).empty()) return f.string();
  return "";
}

std::string readWholeFile(const std::string& path) {
  const std::string problem = fileProblem(path);
  if (!problem.empty()) loadFail(path, "", "cannot open: " + problem);
  std::ifstream in(path, std::ios::binary);
  if (!in) loadFail(path, "", std::string("cannot open: ") + std::strerror(errno));
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) text.append(chunk, static_cast<std::size_t>(in.gcount()));
  if (in.bad()) loadFail(path, "", "read error");
  return text;
}

void checkJsonDepth(const std::string& file, const char* text, std::size_t size) {
  int depth = 0;
  bool inString = false;
  std::size_t line = 1;
  for (std::size_t i = 0; i < size; ++i) {
    const char c = text[i];
    if (c == '\n') ++line;
    if (inString) {
      if (c == '\\') ++i;  // the escaped character is no quote
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        loadFail(file, lineWhere(line), "nesting deeper than " + std::to_string(kMaxJsonDepth) + " arrays/objects");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

std::string folderOf(const std::string& path) {
  std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return "";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string besideFile(const std::string& baseFile, const std::string& name) {
  const std::string dir = folderOf(baseFile);
  if (name.empty() || name[0] == '/' || dir.empty()) return name;
  return dir == "/" ? "/" + name : dir + "/" + name;
}

std::string lowerExtension(const std::string& path) {
  std::size_t slash = path.find_last_of('/');
  std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

bool appendTriangle(Scene& scene, const SceneTriangle& t) {
  const glm::vec3 n = glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
  const bool finite = std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z);
  if (!finite || (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f)) {
    ++scene.degenerateDropped;
    return false;
  }
  bool first = scene.triangles.empty();
  for (const glm::vec3& v : t.v) {
    scene.boundsMin = first ? v : glm::min(scene.boundsMin, v);
    scene.boundsMax = first ? v : glm::max(scene.boundsMax, v);
    first = false;
  }
  scene.triangles.push_back(t);
  return true;
}

namespace {
bool gListEveryWarning = false;
// A file with millions of faulty faces keeps the listing bounded.
constexpr std::size_t kOthersKept = 10000;
}  // namespace

void listEveryWarning(bool all) { gListEveryWarning = all; }

void KindWarnings::add(const std::string& kind, const std::string& where, const std::string& text) {
  auto it = kinds_.find(kind);
  if (it != kinds_.end()) {
    ++it->second.more;
    if (gListEveryWarning && it->second.others.size() < kOthersKept)
      it->second.others.push_back((where.empty() ? "" : oneLine(where) + ": ") + oneLine(text, 400));
    return;
  }
  Entry e;
  e.where = where;
  e.text = text;
  e.order = kinds_.size();
  kinds_.emplace(kind, e);
}

void KindWarnings::flush(std::vector<std::string>* out) const {
  std::vector<const Entry*> order;
  for (const auto& k : kinds_) order.push_back(&k.second);
  std::sort(order.begin(), order.end(), [](const Entry* a, const Entry* b) { return a->order < b->order; });
  if (!out) return;
  for (const Entry* e : order) {
    const std::string first = oneLine(file_, 4096) + ": " + (e->where.empty() ? "" : oneLine(e->where) + ": ") +
                              oneLine(e->text, 400);
    if (!gListEveryWarning) {
      out->push_back(first + (e->more ? " (" + std::to_string(e->more) + " more like it; -v lists them)" : ""));
      continue;
    }
    out->push_back(first);
    for (const std::string& o : e->others) out->push_back(oneLine(file_, 4096) + ": " + o);
    if (e->more > e->others.size())
      out->push_back(oneLine(file_, 4096) + ": (" + std::to_string(e->more - e->others.size()) + " more like it)");
  }
}

}  // namespace montecl
