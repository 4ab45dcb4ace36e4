// pbrt_tokenizer.h: splits a pbrt-v4 scene file's text into tokens (bare words, quoted strings,
// numbers, brackets), each with its file:line:column, for the directive reader (pbrt_scene.cpp).
// Reads only the text it is given; bad input is one InputError "<file>:<line>:<column>: <problem>".
#pragma once
#include <cstddef>
#include <string>

namespace montecl {

// Where a token starts, 1-based; str() is "<file>:<line>:<column>".
struct PbrtLoc {
  std::string file;
  int line = 0, column = 0;
  std::string str() const;
};

// Throws InputError "<file>:<line>:<column>: <problem>" (one line).
[[noreturn]] void pbrtFail(const PbrtLoc& loc, const std::string& problem);

struct PbrtToken {
  enum Kind { Word, String, Number, Open, Close, End } kind = End;
  std::string text;    // the word, the string without its quotes (escapes resolved), the number as written
  double number = 0;   // Number only
  PbrtLoc loc;
};

class PbrtTokenizer {
 public:
  PbrtTokenizer(std::string file, std::string text);
  PbrtToken next();          // the next token (End, repeatedly, at the end of the text)
  const PbrtToken& peek();   // the next token without consuming it
  const std::string& file() const { return file_; }

 private:
  PbrtToken scan();
  std::string file_, text_;
  std::size_t pos_ = 0;
  int line_ = 1;
  std::size_t lineStart_ = 0;
  bool peeked_ = false;
  PbrtToken peekToken_;
};

}  // namespace montecl
