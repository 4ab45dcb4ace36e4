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
#include <optional>
#include <string>
#include <vector>

#include "scene/render_choices.h"

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

// --max-depth: -1 (unlimited) or a positive integer.
inline CLI::Validator maxDepthValue() {
  const std::string rule = "-1 (unlimited) or a positive integer";
  return CLI::Validator(
      [rule](std::string& text) -> std::string {
        errno = 0;
        char* end = nullptr;
        long long v = std::strtoll(text.c_str(), &end, 10);
        bool ok = !text.empty() && end && *end == '\0' && errno == 0 && (v == -1 || (v >= 1 && v <= std::numeric_limits<int>::max()));
        return ok ? std::string() : "must be " + rule + ", got '" + text + "'";
      },
      rule);
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

// An option whose value is one of a choice's names (scene/render_choices.h), stored as the enum:
// only the names are accepted (not the enum's numbers), and help and errors list them.
template <class E>
CLI::Option* addChoiceOption(CLI::App* cmd, const std::string& name, std::optional<E>& target,
                             const ChoiceNames<E>& names, const std::string& help) {
  std::vector<std::string> keys;
  for (const auto& entry : names) keys.push_back(entry.first);
  return cmd
      ->add_option_function<std::string>(
          name, [&target, &names](const std::string& v) { target = names.at(v); },
          help + ": " + choiceList(names, /*quoted=*/false))
      ->check(CLI::IsMember(keys))
      ->type_name("NAME");
}

}  // namespace montecl
