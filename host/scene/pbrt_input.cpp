// pbrt_input.cpp: the .pbrt token stream across Includes (pbrt_input.h): opening files (depth,
// compression and access checked) and the directives' token reads.
#include "scene/pbrt_input.h"

#include "scene/load_util.h"
#include "util/errors.h"

namespace montecl {

namespace {
constexpr int kMaxPbrtIncludeDepth = 32;
}

void PbrtInput::open(const std::string& path, const PbrtLoc& from, std::vector<std::string>& inputFiles) {
  if (int(files_.size()) >= kMaxPbrtIncludeDepth) pbrtFail(from, "Includes nested deeper than " + std::to_string(kMaxPbrtIncludeDepth) + " (an Include cycle?)");
  const std::string problem = fileProblem(path);
  if (!problem.empty()) {
    if (from.line == 0) throwInputError(path, "", "cannot open: " + problem);
    pbrtFail(from, "cannot open '" + oneLine(path, 120) + "': " + problem);
  }
  if (lowerExtension(path) == ".gz") pbrtFail(from, "'" + oneLine(path, 120) + "' is compressed; montecl reads uncompressed .pbrt files only (gunzip it)");
  if (from.line != 0) inputFiles.push_back(path);
  files_.push_back(std::make_unique<PbrtTokenizer>(path, readWholeFile(path)));
}

PbrtToken PbrtInput::expect(PbrtToken::Kind kind, const char* what, const PbrtLoc& directive) {
  PbrtToken t = tok().next();
  if (t.kind != kind)
    pbrtFail(t.kind == PbrtToken::End ? directive : t.loc,
             std::string("expected ") + what + (t.kind == PbrtToken::End ? ", got the end of the file" : ", got '" + oneLine(t.text, 40) + "'"));
  return t;
}

std::string PbrtInput::name(const PbrtToken& d) {
  return expect(PbrtToken::String, ("a quoted name after " + d.text).c_str(), d.loc).text;
}

std::vector<double> PbrtInput::numbers(const PbrtToken& d, int n) {
  const bool bracket = tok().peek().kind == PbrtToken::Open;
  if (bracket) tok().next();
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(expect(PbrtToken::Number, ("a number (" + d.text + " takes " + std::to_string(n) + ")").c_str(), d.loc).number);
  if (bracket) expect(PbrtToken::Close, ("']' after " + d.text + "'s " + std::to_string(n) + " numbers").c_str(), d.loc);
  return v;
}

}  // namespace montecl
