// pbrt_input.h: the token stream of a .pbrt file and the files it Includes (a stack of
// tokenizers, innermost last), with the reads every directive makes: a token of a kind, a quoted
// name, n numbers, a parameter list. Errors are pbrtFail at the token's file:line:column.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "scene/pbrt_params.h"
#include "scene/pbrt_tokenizer.h"

namespace montecl {

class PbrtInput {
 public:
  // Opens path as the innermost file: `from` is the Include naming it (line 0 for the main file,
  // whose problems name the path alone); an Included file is appended to inputFiles.
  void open(const std::string& path, const PbrtLoc& from, std::vector<std::string>& inputFiles);
  bool empty() const { return files_.empty(); }
  void close() { files_.pop_back(); }  // the innermost file, at its end
  PbrtTokenizer& tok() { return *files_.back(); }

  // The next token, which must be of `kind` (`what` names it in the error; `directive` is where
  // the error points at the end of a file).
  PbrtToken expect(PbrtToken::Kind kind, const char* what, const PbrtLoc& directive);
  std::string name(const PbrtToken& d);  // a quoted name after directive d
  // n numbers after directive d, optionally in brackets (pbrt accepts both for every transform).
  std::vector<double> numbers(const PbrtToken& d, int n);
  PbrtParams params(const PbrtToken& d) { return readPbrtParams(tok(), d.loc); }

 private:
  std::vector<std::unique_ptr<PbrtTokenizer>> files_;
};

}  // namespace montecl
