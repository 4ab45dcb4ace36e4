// kernel_source.cpp: kernel text from $MONTECL_KERNEL_DIR (for editing kernels without rebuilding)
// or from the copies embedded at build time, and a small preprocessor that expands
// #include "x" lines (each file once, #pragma once dropped) into one self-contained source with
// #line directives, so the program cache can hash everything the compiler sees and build logs
// still name the original files and lines.
#include "cl/kernel_source.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "util/errors.h"

namespace montecl {

namespace {

// "a/./b/../c.h" -> "a/c.h"; leading ".." that cannot be resolved are kept.
std::string normalise(const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream ss(path);
  std::string part;
  while (std::getline(ss, part, '/')) {
    if (part.empty() || part == ".") continue;
    if (part == ".." && !parts.empty() && parts.back() != "..") {
      parts.pop_back();
    } else {
      parts.push_back(part);
    }
  }
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : "/") + p;
  return out;
}

std::string folderOf(const std::string& path) {
  auto slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

std::string lineDirective(int line, const std::string& file) {
  return "#line " + std::to_string(line) + " \"" + file + "\"\n";
}

void expand(const std::string& path, const std::string& includedFrom, std::set<std::string>& seen,
            std::string& out) {
  if (!seen.insert(path).second) return;
  std::string text;
  try {
    text = kernelFile(path);
  } catch (const RuntimeError& e) {
    if (includedFrom.empty()) throw;
    throw RuntimeError(std::string(e.what()) + " (included from " + includedFrom + ")");
  }
  static const std::regex includeLine(R"re(^\s*#\s*include\s*"([^"]+)".*$)re");
  static const std::regex pragmaOnce(R"(^\s*#\s*pragma\s+once\b.*$)");

  out += lineDirective(1, path);
  std::istringstream in(text);
  std::string line;
  int lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::smatch m;
    if (std::regex_match(line, m, includeLine)) {
      std::string target = normalise(folderOf(path) + m[1].str());
      expand(target, path + ":" + std::to_string(lineNo), seen, out);
      out += lineDirective(lineNo + 1, path);
    } else if (std::regex_match(line, pragmaOnce)) {
      out += "\n";
    } else {
      out += line;
      out += "\n";
    }
  }
}

}  // namespace

std::string kernelFile(const std::string& path) {
  const char* dir = std::getenv("MONTECL_KERNEL_DIR");
  if (dir && *dir) {
    std::string full = std::string(dir) + "/" + path;
    std::ifstream f(full, std::ios::binary);
    if (!f) {
      throw RuntimeError("cannot read kernel file " + full + ": " + std::strerror(errno) +
                         " (MONTECL_KERNEL_DIR is set)");
    }
    std::ostringstream ss;
    ss << f.rdbuf();
    if (f.bad()) throw RuntimeError("cannot read kernel file " + full);
    return ss.str();
  }
  const auto& sources = embeddedKernelSources();
  auto it = sources.find(path);
  if (it == sources.end())
    throw RuntimeError("kernel file kernels/" + path + " is not embedded in montecl");
  return it->second;
}

std::string expandedKernelSource(const std::string& path) {
  std::set<std::string> seen;
  std::string out;
  expand(normalise(path), "", seen, out);
  return out;
}

}  // namespace montecl
