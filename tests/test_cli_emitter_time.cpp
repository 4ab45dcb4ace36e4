// test_cli_emitter_time.cpp: the emitter table's time through the real command: a glTF of ~6k
// triangles whose emissive texture (2048 x 2048, one bright texel) is read through a clamping
// sampler, where each triangle's light weight needs the whole texture, loads and renders in a
// couple of seconds (reading the texture once per triangle took minutes). The time is the child's
// processor time (user + system, from wait4), not the wall clock: a loaded machine stretches the
// wall time of a correct build, while the per-triangle reading costs minutes of processor time
// however quiet the machine. Writes its files in a temporary folder.
#include <doctest/doctest.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.h"
#include "image/image_io.h"
#include "mesh_files.h"
#include "sanitizers.h"

namespace test_file_cli_emitter_time {  // keeps this file's helpers apart in a unity batch

using namespace montecl_test;

namespace {

// An n x n grid of quads (2 n^2 triangles) over [0, 2] x [0, 1.5], UVs over [0, 1]^2.
MeshData grid(int n) {
  MeshData m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float u = float(i) / float(n), v = float(j) / float(n);
      m.positions.insert(m.positions.end(), {2.0f * u, 1.5f * v, 0.0f});
      m.uvs.insert(m.uvs.end(), {u, v});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + std::uint32_t(n + 1) + 1, d = c - 1;
      m.faces.push_back({a, b, c, d});
    }
  return m;
}

// gltfText's model with an emissive texture (emissive.png through a CLAMP_TO_EDGE sampler).
std::string clampedEmissiveGltf(const MeshData& m) {
  std::string text = gltfText(m, 0.5f, "");
  const std::size_t from = text.find(R"("materials":)"), to = text.find(R"(,"buffers":)");
  REQUIRE(from != std::string::npos);
  REQUIRE(to != std::string::npos);
  return text.substr(0, from) +
         R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.5,0.5,1]},)"
         R"("emissiveFactor":[1,1,1],"emissiveTexture":{"index":0}}],)"
         R"("textures":[{"source":0,"sampler":0}],"images":[{"uri":"emissive.png"}],)"
         R"("samplers":[{"wrapS":33071,"wrapT":33071}])" +
         text.substr(to);
}

// Waits for pid up to seconds of wall time; kills it (SIGKILL) past that. Returns its exit status,
// or -1 when it had to be killed; *cpuSeconds: its user + system time.
int waitAtMost(pid_t pid, double seconds, double* cpuSeconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  auto cpu = [](const rusage& u) {
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  };
  for (;;) {
    int status = 0;
    rusage usage{};
    if (wait4(pid, &status, WNOHANG, &usage) == pid) {
      *cpuSeconds = cpu(usage);
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    if (std::chrono::steady_clock::now() > end) {
      kill(pid, SIGKILL);
      wait4(pid, &status, 0, &usage);
      *cpuSeconds = cpu(usage);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

TEST_CASE("cli: a clamped 2048^2 emissive map on ~6k triangles loads and renders in under 2 s of processor time" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  const int side = 2048;
  std::vector<float> rgb(std::size_t(side) * side * 3, 0.0f);
  const std::size_t bright = (std::size_t(side / 3) * side + side / 5) * 3;  // one texel off every grid point
  rgb[bright] = rgb[bright + 1] = rgb[bright + 2] = 1.0f;
  montecl::writeRgbImage(dir.file("emissive.png"), side, side, rgb);
  const MeshData m = grid(55);  // 6050 triangles
  dir.write("lamp.gltf", clampedEmissiveGltf(m));
  const pid_t pid = spawnMontecl({"render", dir.file("lamp.gltf"), "-o", dir.file("lamp.pfm"), "--width", "8",
                                  "--height", "8", "--spp", "1", "--device", "host", "-q"},
                                 dir.file("err.txt"));
  // The budget: 2 s in a release build; sanitizers slow every texel read several times.
  const double budget = MCL_TEST_UNDER_ASAN ? 12.0 : 2.0;
  double seconds = 0.0;
  const int rc = waitAtMost(pid, 60.0, &seconds);
  INFO(readAll(dir.file("err.txt")));
  INFO("processor seconds " << seconds);
  REQUIRE(rc == 0);
  CHECK(seconds < budget);
  CHECK(std::filesystem::exists(dir.file("lamp.pfm")));
}

}  // namespace test_file_cli_emitter_time
