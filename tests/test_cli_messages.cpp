// test_cli_messages.cpp: what `montecl render` says to a new user, through the real command: a bare
// model's default sky (dimmer when it brings its own lights, named with -v, off with --env none),
// the warning for a nearly black image, slow load steps on stderr and signals while loading (exit
// 130 / 143, nothing written), and the messages that name the option that changes the outcome
// (missing textures, a malformed --env, "more like it", "did you mean", MTL names and tinyobj's
// warnings, the grouped --help). Writes its files in a temporary folder.
#include <doctest/doctest.h>

#include <signal.h>
#include <stdlib.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "cli_checks.h"
#include "cli_runner.h"

namespace test_file_cli_messages {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;

namespace {

// A grey quad facing +z and, beside it, a small triangle of emission `ke` (a lamp's bulb).
void writeLamp(const TempDir& dir, const std::string& ke) {
  dir.write("lamp.mtl", "newmtl body\nKd 0.8 0.8 0.8\nnewmtl bulb\nKd 0 0 0\nKe " + ke + " " + ke + " " + ke + "\n");
  dir.write("lamp.obj",
            "mtllib lamp.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv 1.1 0.9 0.2\nv 1.2 0.9 0.2\nv 1.15 1 0.2\n"
            "usemtl body\nf 1 2 3 4\nusemtl bulb\nf 5 6 7\n");
}

std::vector<std::string> small(const TempDir& dir, const std::string& in, const std::string& out) {
  return {"render", dir.file(in), "-o", dir.file(out), "--width", "16", "--height", "16", "--spp", "4",
          "--device", "host", "-q"};
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Sets an environment variable for the processes this test starts, restoring it after.
struct ScopedEnv {
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = ::getenv(name)) had_ = true, old_ = old;
    ::setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (had_)
      ::setenv(name_, old_.c_str(), 1);
    else
      ::unsetenv(name_);
  }
  const char* name_;
  bool had_ = false;
  std::string old_;
};

// Starts a render that pauses in its first load step, signals it once the step's line is on
// stderr, and checks the exit status, the line and that nothing was written.
void signalWhileLoading(int sig, int status, const std::string& said) {
  TempDir dir;
  writeLamp(dir, "4");
  ScopedEnv pause("MONTECL_TEST_LOAD_PAUSE_S", "20");
  std::vector<std::string> args = small(dir, "lamp.obj", "out.png");
  args.pop_back();  // not -q: the step's line shows the load has begun
  const pid_t pid = spawnMontecl(args, dir.file("err.txt"));
  for (int i = 0; i < 400 && !has(readAll(dir.file("err.txt")), "reading "); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const std::string before = readAll(dir.file("err.txt"));
  INFO(before);
  CHECK(has(before, "montecl: reading " + dir.file("lamp.obj") + " ..."));
  const auto sent = std::chrono::steady_clock::now();
  kill(pid, sig);
  CHECK(waitFor(pid) == status);
  CHECK(std::chrono::steady_clock::now() - sent < std::chrono::seconds(10));  // at once, not after the pause
  CHECK(has(readAll(dir.file("err.txt")), said));
  CHECK_FALSE(std::filesystem::exists(dir.file("out.png")));
}

}  // namespace

TEST_CASE("cli: a bare model keeps a sky (dimmer when it emits, named by -v); --env none turns it off" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  writeLamp(dir, "4");
  std::vector<std::string> a = small(dir, "lamp.obj", "lit.png");
  a.push_back("-v");
  const CliResult lit = runMontecl(a);
  INFO(lit.err);
  REQUIRE(lit.exitCode == 0);
  CHECK(has(lit.err, "montecl: environment: a white sky of radiance 0.25 (the model brings its own lights; --env none"));
  CHECK_FALSE(has(lit.err, "nearly black"));
  // Without lights of its own the model gets the full sky.
  dir.write("plain.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nf 1 2 3\n");
  std::vector<std::string> p = small(dir, "plain.obj", "plain.png");
  p.push_back("-v");
  const CliResult plain = runMontecl(p);
  INFO(plain.err);
  REQUIRE(plain.exitCode == 0);
  CHECK(has(plain.err, "montecl: environment: a white sky of radiance 1 "));
  // --env replaces the default, so -v does not name it.
  p[3] = dir.file("none.png");
  p.insert(p.end(), {"--env", "none"});
  const CliResult none = runMontecl(p);
  INFO(none.err);
  REQUIRE(none.exitCode == 0);
  CHECK_FALSE(has(none.err, "montecl: environment:"));
}

TEST_CASE("cli: a nearly black image warns with its likely cause and the option that changes it" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  writeLamp(dir, "0.001");  // a faint bulb: with no sky the frame is black
  std::vector<std::string> a = small(dir, "lamp.obj", "dark.png");
  a.insert(a.end(), {"--env", "none"});
  const CliResult dark = runMontecl(a);
  INFO(dark.err);
  REQUIRE(dark.exitCode == 0);
  CHECK(has(dark.err, "montecl: warning: " + dir.file("lamp.obj") + ": the image is nearly black"));
  CHECK(has(dark.err, "no environment lights it"));
  CHECK(has(dark.err, "--env 1,1,1"));
  CHECK(std::filesystem::exists(dir.file("dark.png")));  // a warning: the image is still written
  // The default sky lights the same model: no warning.
  const CliResult sky = runMontecl(small(dir, "lamp.obj", "sky.png"));
  INFO(sky.err);
  REQUIRE(sky.exitCode == 0);
  CHECK_FALSE(has(sky.err, "nearly black"));
  // A dim sky names --env-scale.
  std::vector<std::string> d = small(dir, "lamp.obj", "dim.png");
  d.insert(d.end(), {"--env", "0.001,0.001,0.001"});
  const CliResult dim = runMontecl(d);
  INFO(dim.err);
  CHECK(has(dim.err, "the environment (radiance 0.001) is dim"));
  CHECK(has(dim.err, "--env-scale"));
}

TEST_CASE("cli: a load step over a second is named on stderr with its time; -q keeps it quiet" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  writeLamp(dir, "4");
  std::vector<std::string> a = small(dir, "lamp.obj", "out.png");
  a.pop_back();  // not -q
  const CliResult r = runMontecl(a, {"MONTECL_TEST_LOAD_PAUSE_S=1.5"});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(has(r.err, "montecl: reading " + dir.file("lamp.obj") + " ...\n"));
  CHECK(has(r.err, "montecl: reading " + dir.file("lamp.obj") + ": done in "));
  // Steps under a second say nothing.
  CHECK_FALSE(has(r.err, "building the BVH"));
  a.push_back("-q");
  a[3] = dir.file("quiet.png");
  const CliResult q = runMontecl(a, {"MONTECL_TEST_LOAD_PAUSE_S=1.5"});
  CHECK(q.exitCode == 0);
  CHECK_FALSE(has(q.err, "reading"));
}

TEST_CASE("cli: SIGTERM while loading ends the render at once: exit 143, nothing written" *
          doctest::test_suite("cli sanitize slow")) {
  signalWhileLoading(SIGTERM, 143, "montecl: terminated while loading; nothing written\n");
}

TEST_CASE("cli: SIGINT while loading ends the render at once: exit 130, nothing written" *
          doctest::test_suite("cli sanitize slow")) {
  signalWhileLoading(SIGINT, 130, "montecl: interrupted while loading; nothing written\n");
}

TEST_CASE("cli: messages name the option or value that changes the outcome" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string out = dir.file("out.png");
  dir.write("tri.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl paint\nf 1 2 3\n");
  dir.write("t.mtl", "newmtl paint\nmap_Kd gone.png\n");
  // A missing texture names --missing-textures warn.
  checkRefused(runMontecl(small(dir, "tri.obj", "out.png")), out, {"gone.png", "--missing-textures warn"});
  // --env with two numbers says what the value should be, not "cannot open".
  dir.write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  std::vector<std::string> env = small(dir, "plain.obj", "out.png");
  env.insert(env.end(), {"--env", "1,1"});
  const CliResult e = runMontecl(env);
  checkRefused(e, out, {"--env", "'1,1'", "R,G,B", "1,1,1"});
  CHECK_FALSE(has(e.err, "cannot open"));
  env.back() = "1,x,1";
  checkRefused(runMontecl(env), out, {"--env", "'1,x,1'", "R,G,B"});
  // A mistyped option or command gets the nearest name.
  std::vector<std::string> typo = small(dir, "plain.obj", "out.png");
  typo.insert(typo.end(), {"--integrater", "path"});
  checkRefused(runMontecl(typo), out, {"unknown option '--integrater'", "did you mean '--integrator'?"});
  std::vector<std::string> rendr = small(dir, "plain.obj", "out.png");
  rendr[0] = "rendr";
  checkRefused(runMontecl(rendr), out, {"unknown command 'rendr'", "did you mean 'render'?"});
}

TEST_CASE("cli: repeated warnings say what the count is and that -v lists them" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("wire.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\nl 2 3\nl 3 1\n");
  const CliResult r = runMontecl(small(dir, "wire.obj", "a.png"));
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(has(r.err, "wire.obj: line 5: 'l' (lines) not rendered by montecl, ignored (2 more like it; -v lists them)\n"));
  std::vector<std::string> v = small(dir, "wire.obj", "b.png");
  v.push_back("-v");
  const CliResult all = runMontecl(v);
  INFO(all.err);
  REQUIRE(all.exitCode == 0);
  for (const char* line : {"line 5", "line 6", "line 7"})
    CHECK(has(all.err, std::string("wire.obj: ") + line + ": 'l' (lines) not rendered by montecl, ignored\n"));
  CHECK_FALSE(has(all.err, "more like it"));
}

TEST_CASE("cli: MTL names after two blanks are found; tinyobj's 'Both d and Tr' names the MTL" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("car.obj", "mtllib car.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl RearLights\nf 1 2 3\n");
  dir.write("car.mtl", "newmtl  RearLights\nKd 1 0 0\nd 1\nTr 0\n");
  const CliResult r = runMontecl(small(dir, "car.obj", "car.png"));
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK_FALSE(has(r.err, "not found"));
  CHECK(has(r.err, "montecl: warning: " + dir.file("car.mtl") +
                       ": line 4: material 'RearLights' gives both d and Tr (opacity, written twice): Tr ignored\n"));
  CHECK_FALSE(has(r.err, "car.obj: Both"));
}

TEST_CASE("cli: render --help lists the common options first and the tuning knobs in their own group" *
          doctest::test_suite("cli sanitize")) {
  const CliResult r = runMontecl({"render", "--help"});
  REQUIRE(r.exitCode == 0);
  const std::string& h = r.out;
  const std::size_t tuning = h.find("\nTuning (");
  REQUIRE(tuning != std::string::npos);
  for (const char* common : {"--output", "--width", "--integrator", "--spp", "--env ", "--view", "--device"}) {
    INFO(common);
    REQUIRE(h.find(common) != std::string::npos);
    CHECK(h.find(common) < h.find("\nIntegrator and sampling settings"));
  }
  for (const char* knob : {"--wave-size", "--lanes", "--no-fuse", "--bvh-layout", "--work-group-size"}) {
    INFO(knob);
    CHECK(h.find(knob) > tuning);
  }
  // The default a bare model gets beside the scene file's.
  CHECK(has(h, "default ao; path for a bare model"));
  CHECK(has(h, "or none (a bare model gets a white sky"));
}

}  // namespace test_file_cli_messages
