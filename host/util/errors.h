// errors.h: the two kinds of failure montecl reports, and the exit codes they map to.
#pragma once
#include <stdexcept>
#include <string>

namespace montecl {

constexpr int kExitOk = 0;
constexpr int kExitRuntime = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitInterrupted = 130;  // SIGINT stopped a render early (128 + 2)
constexpr int kExitTerminated = 143;   // SIGTERM stopped a render early (128 + 15)

// Bad input from the user (files, options). what() is one line: "<file>: <key or line N>: <problem>".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A failure of the machine or a library (OpenCL call, kernel build, write error).
class RuntimeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "<file>: <where>: <problem>" (where may be empty), thrown as InputError.
[[noreturn]] void throwInputError(const std::string& file, const std::string& where,
                                  const std::string& problem);

}  // namespace montecl
