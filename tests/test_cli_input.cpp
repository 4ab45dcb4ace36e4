// test_cli_input.cpp: command-line input rules of `montecl render` (host/cli/validators.h): every
// numeric option is checked before any work, with a short message (no 300-digit bounds), NaN and
// infinity are refused, and the image size and light samples follow the scene file's limits.
#include <doctest/doctest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <regex>

#include "cli_runner.h"

using montecl_test::CliResult;
using montecl_test::runMontecl;
using montecl_test::TempDir;
namespace fs = std::filesystem;

namespace {

const std::string kGoodScene = std::string(MONTECL_SOURCE_DIR) + "/scenes/test/good/scene.json";

// `montecl render <good scene> -o tmp/out.png <option> <value>`: exit 2, the message, no output.
std::string badOption(const std::string& option, const std::string& value) {
  TempDir dir;
  CliResult r = runMontecl({"render", kGoodScene, "-q", "-o", dir.file("out.png"), option, value});
  INFO(option << " " << value << ": stderr: " << r.err);
  CHECK(r.exitCode == 2);
  CHECK(!fs::exists(dir.file("out.png")));
  CHECK(r.err.find(option) != std::string::npos);
  CHECK(!std::regex_search(r.err, std::regex("[0-9]{20}")));  // no 300-digit bounds
  return r.err;
}

}  // namespace

TEST_CASE("cli: integer options out of range say 'must be a positive integer'" * doctest::test_suite("cli")) {
  for (const char* opt : {"--spp", "--width", "--height", "--light-samples", "--wave-size", "--work-group-size"})
    for (const char* value : {"0", "-3", "1.5", "nan"}) {
      std::string err = badOption(opt, value);
      CHECK_MESSAGE(err.find("must be a positive integer") != std::string::npos, opt << " " << value << ": " << err);
    }
}

TEST_CASE("cli: float options refuse zero, NaN and infinity: 'must be a positive number'" * doctest::test_suite("cli")) {
  for (const char* opt : {"--ao-distance", "--target-error", "--time"})
    for (const char* value : {"0", "-1", "nan", "NaN", "inf", "-inf", "1e999"}) {
      std::string err = badOption(opt, value);
      CHECK_MESSAGE(err.find("must be a positive number") != std::string::npos, opt << " " << value << ": " << err);
    }
  // --ao-distance is a float: a double beyond the float range would become inf.
  CHECK(badOption("--ao-distance", "1e39").find("up to 3.40282e+38") != std::string::npos);
}

TEST_CASE("cli: --width/--height follow the scene file's 16384 cap; --light-samples its 1024 cap" * doctest::test_suite("cli")) {
  CHECK(badOption("--width", "16385").find("up to 16384") != std::string::npos);
  CHECK(badOption("--height", "20000").find("up to 16384") != std::string::npos);
  CHECK(badOption("--light-samples", "1025").find("up to 1024") != std::string::npos);
  CHECK(badOption("--light-samples", "1000000").find("up to 1024") != std::string::npos);
  // The largest allowed values pass the option check (tiny render: the other side stays small).
  TempDir dir;
  CliResult r = runMontecl({"render", kGoodScene, "-q", "-o", dir.file("out.png"), "--width", "16384", "--height",
                            "1", "--spp", "1", "--integrator", "direct", "--light-samples", "1024"});
  INFO("stderr: " << r.err);
  CHECK(r.exitCode == 0);
}
