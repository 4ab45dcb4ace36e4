// terrain.cpp: height field = sum of seeded sine octaves over a grid of w x h cells (two triangles
// each), filled row by row and cut off at exactly N triangles; fast buffered OBJ writing.
#include "bench/terrain.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "kernels/shared/rng.h"
#include "scene/render_choices.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace montecl {
namespace {

struct Octave {
  float fx, fz, phase, amp;
};

std::vector<Octave> octaves(std::uint32_t seed, float size) {
  std::vector<Octave> o;
  float amp = size * 0.08f, freq = 2.0f * 3.14159265f / size;
  for (uint k = 0; k < 8; ++k) {
    float4 u = rng_uniform4(seed, k, 0, 7);
    float angle = 6.2831853f * u.x;
    o.push_back({freq * std::cos(angle) * (1.0f + u.y), freq * std::sin(angle) * (1.0f + u.y), 6.2831853f * u.z, amp});
    amp *= 0.55f;
    freq *= 2.1f;
  }
  return o;
}

void checkFolder(const std::string& path) {
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (!dir.empty() && !std::filesystem::is_directory(dir))
    throwInputError(path, "", "output folder '" + dir.string() + "' does not exist");
}

void writeText(const std::string& path, const std::string& text) {
  writeAtomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw RuntimeError(path + ": write failed");
  });
}

}  // namespace

std::uint64_t writeTerrainObj(const std::string& objPath, const TerrainOptions& opt) {
  if (opt.triangles < 1) throwInputError(objPath, "", "--triangles must be at least 1");
  checkFolder(objPath);
  const std::uint64_t cells = (opt.triangles + 1) / 2;
  const std::uint64_t w = std::max<std::uint64_t>(1, std::uint64_t(std::llround(std::sqrt(double(cells)))));
  const std::uint64_t h = (cells + w - 1) / w;
  const std::vector<Octave> oct = octaves(opt.seed, opt.size);
  writeAtomically(objPath, [&](const std::string& tmp) {
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw RuntimeError(objPath + ": cannot write");
    std::vector<char> buf(1 << 20);
    std::setvbuf(f, buf.data(), _IOFBF, buf.size());
    std::fprintf(f, "# montecl generate terrain: %llu triangles, seed %u, %llux%llu cells\n",
                 (unsigned long long)opt.triangles, opt.seed, (unsigned long long)w, (unsigned long long)h);
    for (std::uint64_t j = 0; j <= h; ++j)
      for (std::uint64_t i = 0; i <= w; ++i) {
        float x = opt.size * (float(i) / float(w) - 0.5f), z = opt.size * (float(j) / float(h) - 0.5f);
        float y = 0.0f;
        for (const Octave& o : oct) y += o.amp * std::sin(o.fx * x + o.fz * z + o.phase);
        std::fprintf(f, "v %.6g %.6g %.6g\n", x, y, z);
      }
    std::uint64_t written = 0;
    for (std::uint64_t c = 0; c < cells; ++c) {
      std::uint64_t i = c % w, j = c / w;
      unsigned long long a = j * (w + 1) + i + 1, b = a + 1, d = a + (w + 1), e = d + 1;  // 1-based
      std::fprintf(f, "f %llu %llu %llu\n", a, d, b);
      if (++written == opt.triangles) break;
      std::fprintf(f, "f %llu %llu %llu\n", b, d, e);
      ++written;
    }
    bool ok = std::ferror(f) == 0;
    ok = (std::fclose(f) == 0) && ok;
    if (!ok) throw RuntimeError(objPath + ": write failed");
  });
  return opt.triangles;
}

void writeTerrainScene(const std::string& scenePath, const std::string& objPath, const TerrainOptions& opt,
                       int width, int height) {
  namespace fs = std::filesystem;
  checkFolder(scenePath);
  fs::path sceneDir = fs::path(scenePath).parent_path();
  fs::path lightPath = sceneDir / (fs::path(scenePath).stem().string() + "-light.obj");
  float s = opt.size, ly = s * 0.8f, lh = s * 0.1f;
  char light[512];
  std::snprintf(light, sizeof light,
                "# montecl generate terrain: emissive quad above the terrain\n"
                "v %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\nf 1 2 3\nf 1 3 4\n",
                -lh, ly, -lh, lh, ly, -lh, lh, ly, lh, -lh, ly, lh);
  writeText(lightPath.string(), light);
  fs::path objRel = fs::absolute(objPath).lexically_relative(fs::absolute(sceneDir.empty() ? "." : sceneDir));
  nlohmann::json j = {
      {"camera",
       {{"position", {0.0f, s * 0.45f, s * 0.85f}},
        {"target", {0.0f, 0.0f, 0.0f}},
        {"up", {0, 1, 0}},
        {"fov_y", 50},
        {"width", width},
        {"height", height}}},
      {"meshes", {{{"file", objRel.string()}}, {{"file", lightPath.filename().string()}, {"emission", {20, 20, 20}}}}},
      {"render", {{"integrator", choiceName(Integrator::Ao)}, {"spp", 16}, {"seed", opt.seed}, {"ao_distance", s / 20.0f}}}};
  writeText(scenePath, j.dump(2) + "\n");
}

}  // namespace montecl
