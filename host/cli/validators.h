// validators.h: CLI11 checks with short messages ("--spp: must be a positive integer") instead of
// CLI11's ranges, which print the bound 1.79e308 as a 300-digit number. Numbers must be finite:
// nan and inf are refused. Validators run on the option's text before it is converted.
#pragma once
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>


namespace montecl {

// An integer in [lo, hi]; the message names the rule ("must be a positive integer up to 16384").
inline CLI::Validator integerIn(long long lo, long long hi, const std::string& rule) {
  return CLI::Validator(
      [lo, hi, rule](std::string& text) -> std::string {
        errno = 0;
        char* end = nullptr;
        long long v = std::strtoll(text.c_str(), &end, 10);
        bool ok = !text.empty() && end && *end == '\0' && errno == 0 && v >= lo && v <= hi;
        return ok ? std::string() : "must be " + rule + ", got '" + text + "'";
      },
      rule);
}

inline CLI::Validator positiveInteger(long long hi = std::numeric_limits<int>::max()) {
  return integerIn(1, hi, hi == std::numeric_limits<int>::max() ? std::string("a positive integer")
                                                                   : "a positive integer up to " + std::to_string(hi));
}

inline std::string shortNumber(double v) {
  std::ostringstream s;
  s << v;  // 6 significant digits: 3.40282e+38
  return s.str();
}

// A finite number > 0 and at most hi (float options pass FLT_MAX so they cannot overflow to inf).
inline CLI::Validator positiveNumber(double hi = std::numeric_limits<double>::max()) {
  return CLI::Validator(
      [hi](std::string& text) -> std::string {
        char* end = nullptr;
        double v = std::strtod(text.c_str(), &end);
        bool number = !text.empty() && end && *end == '\0' && std::isfinite(v);
        if (number && v > hi) return "must be a positive number up to " + shortNumber(hi) + ", got '" + text + "'";
        return number && v > 0.0 ? std::string() : "must be a positive number, got '" + text + "'";
      },
      "a positive number");
}

// A finite number in [lo, hi]: CLI::Range lets NaN through (every comparison with it is false).
inline CLI::Validator finiteIn(double lo, double hi) {
  const std::string rule = "a number from " + shortNumber(lo) + " to " + shortNumber(hi);
  return CLI::Validator(
      [lo, hi, rule](std::string& text) -> std::string {
        char* end = nullptr;
        double v = std::strtod(text.c_str(), &end);
        bool number = !text.empty() && end && *end == '\0' && std::isfinite(v);
        return number && v >= lo && v <= hi ? std::string() : "must be " + rule + ", got '" + text + "'";
      },
      rule);
}

}  // namespace montecl
