// test_cli_checkpoint.cpp: --checkpoint and --resume through the command line. The checkpoint
// path is checked before any work (not an input, not the output, not a foreign file, creatable);
// a checkpoint that cannot be written later is a warning and the image is still written; --resume
// takes regular files only (a FIFO, a folder: one line, exit 2, at once); and a checkpoint resumes
// only the render it was made by: after a change of the environment map, a specular lobe, an albedo
// texture's pixels, an alpha cutoff or two-sided emission it is "a checkpoint of another render".
#include <doctest/doctest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <thread>

#include "cli_runner.h"
#include "image/image_io.h"


namespace test_file_cli_checkpoint {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;  // runMontecl, renderOnHost, oneLine, TempDir, ... (fixtures/cli_runner.h)
namespace fs = std::filesystem;

namespace {

// Scene parameters a checkpoint must notice.
struct Params {
  float sky = 0.5f;          // the environment map's value (its pixels, same file name)
  float specular = 0.2f;     // material override "specular"
  float texture = 0.25f;     // the albedo texture's value (its pixels, same file name)
  float alphaCutoff = 0.5f;  // "alpha_cutoff"
  bool twoSided = false;     // "two_sided_emission"
};

std::string num(float v) { return std::to_string(v); }

// A textured, emitting, glossy quad under an environment map, 8x8 pixels, direct lighting. The
// texture and the map are written when `images` names them ("tex", "sky", "all"): a change of one
// file leaves the others' bytes as they were.
std::string writeScene(const TempDir& dir, const Params& p, const std::string& images = "all") {
  dir.write("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n");
  if (images == "all" || images == "tex") montecl::writeRgbImage(dir.file("tex.png"), 2, 2, std::vector<float>(12, p.texture));
  if (images == "all" || images == "sky") montecl::writeRgbImage(dir.file("sky.exr"), 8, 4, std::vector<float>(96, p.sky));
  const std::string s = num(p.specular);
  dir.write("scene.json", R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 45, "width": 8, "height": 8},
    "meshes": [{"file": "quad.obj", "material": {"albedo_texture": "tex.png", "alpha_cutoff": )" + num(p.alphaCutoff) +
                              R"(, "specular": [)" + s + ", " + s + ", " + s + R"(], "specular_exponent": 20,
      "emission": [0.5, 0.5, 0.5], "two_sided_emission": )" + (p.twoSided ? "true" : "false") + R"(}}],
    "render": {"integrator": "direct", "spp": 8},
    "environment": {"file": "sky.exr"}})");
  return dir.file("scene.json");
}

std::vector<std::string> renderArgs(const std::string& scene, const std::string& out, std::vector<std::string> extra) {
  std::vector<std::string> args{"render", scene, "-o", out, "-q", "--device", "host", "--wave-size", "16"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

}  // namespace

TEST_CASE("checkpoint: --resume after a change of environment, specular, texture, alpha cutoff or two-sided emission is refused" * doctest::test_suite("cli sanitize")) {
  struct Change {
    const char* name;
    std::function<void(Params&)> apply;
    const char* images;  // the image file whose pixels change ("": none; the scene file stays the same otherwise)
  };
  const std::vector<Change> changes = {
      {"environment map pixels", [](Params& p) { p.sky = 0.75f; }, "sky"},
      {"specular", [](Params& p) { p.specular = 0.3f; }, ""},
      {"albedo texture pixels", [](Params& p) { p.texture = 0.75f; }, "tex"},
      {"alpha cutoff", [](Params& p) { p.alphaCutoff = 0.3f; }, ""},
      {"two-sided emission", [](Params& p) { p.twoSided = true; }, ""},
  };
  for (const Change& c : changes) {
    TempDir dir;
    Params p;
    const std::string scene = writeScene(dir, p);
    const std::string ckpt = dir.file("render.ckpt");
    CliResult first = runMontecl(renderArgs(scene, dir.file("a.exr"), {"--checkpoint", ckpt, "--checkpoint-every", "0.000001"}));
    REQUIRE_MESSAGE(first.exitCode == 0, first.err);
    REQUIRE(fs::exists(ckpt));
    // The same scene resumes (the refusal below is the change, not the checkpoint).
    CliResult same = runMontecl(renderArgs(scene, dir.file("b.exr"), {"--resume", ckpt}));
    REQUIRE_MESSAGE(same.exitCode == 0, same.err);
    c.apply(p);
    writeScene(dir, p, c.images);
    CliResult r = runMontecl(renderArgs(scene, dir.file("c.exr"), {"--resume", ckpt}));
    INFO(c.name << ": exit " << r.exitCode << ": " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.find("checkpoint of another render") != std::string::npos);
    CHECK(!fs::exists(dir.file("c.exr")));
  }
}

TEST_CASE("checkpoint: a --checkpoint that is an input, the output, a foreign file or uncreatable is refused before any work" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string scene = writeScene(dir, Params{});
  dir.write("notes.txt", "my notes\n");
  const std::string sceneBefore = readAll(scene), texBefore = readAll(dir.file("tex.png")), notes = readAll(dir.file("notes.txt"));
  const std::string out = dir.file("out.exr");
  for (const std::string& ckpt : {scene, dir.file("tex.png"), dir.file("quad.obj"), out, dir.file("notes.txt"),
                                  dir.file("no-folder/render.ckpt"), dir.path, std::string("/proc/montecl.ckpt")}) {
    // A bad device too: the checkpoint is refused before the device is chosen and any work.
    CliResult r = runMontecl({"render", scene, "-o", out, "-q", "--device", "9:9", "--checkpoint", ckpt});
    INFO(ckpt << ": exit " << r.exitCode << ": " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.find(ckpt) != std::string::npos);
    CHECK(r.err.find("9:9") == std::string::npos);
  }
  CHECK(readAll(scene) == sceneBefore);
  CHECK(readAll(dir.file("tex.png")) == texBefore);
  CHECK(readAll(dir.file("notes.txt")) == notes);
  CHECK(!fs::exists(out));
  // A checkpoint resumed and kept: --resume X --checkpoint X is the way to continue.
  const std::string ckpt = dir.file("render.ckpt");
  CliResult a = runMontecl(renderArgs(scene, dir.file("a.exr"), {"--checkpoint", ckpt, "--checkpoint-every", "0.000001"}));
  REQUIRE_MESSAGE(a.exitCode == 0, a.err);
  CliResult b = runMontecl(renderArgs(scene, dir.file("b.exr"), {"--resume", ckpt, "--checkpoint", ckpt}));
  CHECK_MESSAGE(b.exitCode == 0, b.err);
  // The output may not replace the checkpoint it resumes.
  const std::string ckptBefore = readAll(ckpt);
  fs::copy_file(ckpt, dir.file("render.exr"));
  CliResult c = runMontecl(renderArgs(scene, dir.file("render.exr"), {"--resume", dir.file("render.exr")}));
  CHECK(c.exitCode == 2);
  CHECK(oneLine(c.err));
  CHECK(readAll(dir.file("render.exr")) == ckptBefore);
}

TEST_CASE("checkpoint: a checkpoint write that fails mid-render is a warning; the image is still written" * doctest::test_suite("cli sanitize slow")) {
  TempDir dir;
  fs::create_directory(dir.file("ckpts"));
  const std::string ckpt = dir.file("ckpts/render.ckpt"), out = dir.file("out.exr"), err = dir.file("err.txt");
  std::vector<std::string> args = montecl_test::demoRenderArgs(out, 400, 0);
  args.insert(args.end(), {"--device", "host", "--wave-size", "64", "--checkpoint", ckpt, "--checkpoint-every", "0.000001"});
  const pid_t pid = spawnMontecl(args, err);
  for (int i = 0; i < 40000 && !fs::exists(ckpt); ++i) std::this_thread::sleep_for(std::chrono::microseconds(500));
  REQUIRE(fs::exists(ckpt));
  // Every later checkpoint write fails: its folder is gone (moved away at once, whatever the render
  // is writing in it now).
  fs::rename(dir.file("ckpts"), dir.file("moved"));
  const bool stillRunning = waitpid(pid, nullptr, WNOHANG) == 0;
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  const std::string stderrText = readAll(err);
  INFO("stderr: " << stderrText);
  CHECK(stillRunning);  // else the render ended before the folder went: the test proves less
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(fs::exists(out));
  CHECK(stderrText.find("warning: " + ckpt + ": checkpoint not written") != std::string::npos);
  CHECK(std::count(stderrText.begin(), stderrText.end(), '\n') == 1);  // warned once, not every wave
}

TEST_CASE("checkpoint: --resume of a FIFO, a folder or a device is one line, exit 2, at once" * doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const std::string scene = writeScene(dir, Params{});
  REQUIRE(::mkfifo(dir.file("fifo.ckpt").c_str(), 0600) == 0);
  fs::create_directory(dir.file("folder.ckpt"));
  // A montecl that opens the FIFO blocks until a writer comes: this thread is that writer after
  // 5 s (then the reader sees an empty file), so the test ends either way.
  std::atomic<bool> done{false};
  std::thread writer([&] {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (!done && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    while (!done) {
      const int fd = ::open(dir.file("fifo.ckpt").c_str(), O_WRONLY | O_NONBLOCK);
      if (fd >= 0) {
        ::close(fd);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  for (const std::string& resume : {dir.file("fifo.ckpt"), dir.file("folder.ckpt"), std::string("/dev/zero")}) {
    const auto start = std::chrono::steady_clock::now();
    CliResult r = runMontecl(renderArgs(scene, dir.file("out.exr"), {"--resume", resume}));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    INFO(resume << ": exit " << r.exitCode << ": " << r.err);
    CHECK(r.exitCode == 2);
    CHECK(oneLine(r.err));
    CHECK(r.err.find(resume + ": --resume: ") != std::string::npos);
    CHECK(seconds < 5.0);
    CHECK(!fs::exists(dir.file("out.exr")));
  }
  done = true;
  writer.join();
}

}  // namespace test_file_cli_checkpoint
