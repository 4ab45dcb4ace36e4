// pbrt_tokenizer.cpp: the pbrt-v4 tokenizer (pbrt_tokenizer.h): reads a file's text, writes tokens.
// As pbrt's own: '#' starts a comment to the end of the line, strings are double-quoted and may
// not span lines, '[' and ']' are tokens of their own, anything else up to whitespace, a quote or
// a bracket is one word; a word that starts like a number must be one whole number.
#include "scene/pbrt_tokenizer.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <utility>

#include "scene/load_util.h"
#include "util/errors.h"

namespace montecl {

std::string PbrtLoc::str() const { return file + ":" + std::to_string(line) + ":" + std::to_string(column); }

void pbrtFail(const PbrtLoc& loc, const std::string& problem) { throw InputError(oneLine(loc.str() + ": " + problem, 400)); }

PbrtTokenizer::PbrtTokenizer(std::string file, std::string text) : file_(std::move(file)), text_(std::move(text)) {}

const PbrtToken& PbrtTokenizer::peek() {
  if (!peeked_) peekToken_ = scan(), peeked_ = true;
  return peekToken_;
}

PbrtToken PbrtTokenizer::next() {
  if (peeked_) {
    peeked_ = false;
    return std::move(peekToken_);
  }
  return scan();
}

PbrtToken PbrtTokenizer::scan() {
  const std::size_t n = text_.size();
  for (;;) {  // whitespace and comments
    while (pos_ < n && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\r' || text_[pos_] == '\n')) {
      if (text_[pos_] == '\n') ++line_, lineStart_ = pos_ + 1;
      ++pos_;
    }
    if (pos_ < n && text_[pos_] == '#') {
      while (pos_ < n && text_[pos_] != '\n') ++pos_;
      continue;
    }
    break;
  }
  PbrtToken t;
  t.loc = {file_, line_, int(pos_ - lineStart_) + 1};
  if (pos_ >= n) return t;  // End
  const char c = text_[pos_];
  if (c == '[' || c == ']') {
    t.kind = c == '[' ? PbrtToken::Open : PbrtToken::Close;
    t.text = std::string(1, c);
    ++pos_;
    return t;
  }
  if (c == '"') {
    t.kind = PbrtToken::String;
    ++pos_;
    for (;;) {
      if (pos_ >= n || text_[pos_] == '\n') pbrtFail(t.loc, "unterminated string (a string ends with \" on its line)");
      char d = text_[pos_++];
      if (d == '"') break;
      if (d == '\\') {
        if (pos_ >= n) pbrtFail(t.loc, "unterminated string");
        d = text_[pos_++];
        switch (d) {
          case 'n': d = '\n'; break;
          case 't': d = '\t'; break;
          case 'r': d = '\r'; break;
          case 'b': d = '\b'; break;
          case 'f': d = '\f'; break;
          default: break;  // \\, \", \' and any other character: itself
        }
      }
      t.text += d;
    }
    return t;
  }
  const std::size_t start = pos_;
  while (pos_ < n) {
    const char d = text_[pos_];
    if (d == ' ' || d == '\t' || d == '\r' || d == '\n' || d == '"' || d == '[' || d == ']' || d == '#') break;
    ++pos_;
  }
  t.text = text_.substr(start, pos_ - start);
  if ((c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.') {
    t.kind = PbrtToken::Number;
    errno = 0;
    char* end = nullptr;
    t.number = std::strtod(t.text.c_str(), &end);
    if (end != t.text.c_str() + t.text.size() || !std::isfinite(t.number))
      pbrtFail(t.loc, "malformed number '" + oneLine(t.text, 40) + "'");
    return t;
  }
  t.kind = PbrtToken::Word;
  return t;
}

}  // namespace montecl
