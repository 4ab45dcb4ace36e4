// errors.cpp: formatting of input errors.
#include "util/errors.h"

namespace montecl {

void throwInputError(const std::string& file, const std::string& where, const std::string& problem) {
  std::string msg = file;
  if (!where.empty()) msg += ": " + where;
  msg += ": " + problem;
  throw InputError(msg);
}

}  // namespace montecl
