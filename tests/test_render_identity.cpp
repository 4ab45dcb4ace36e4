// test_render_identity.cpp: the render identity (checkpoint key, merge provenance) holds every
// setting that can change a pixel: each row of the settings table changes the key or is named
// here with the reason it need not; every `montecl render` option outside the table is classed;
// and --texture-budget, which drops mip levels, keeps --resume and merge from mixing renders.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "cli_runner.h"
#include "image/image_io.h"
#include "render/checkpoint.h"
#include "render/wavefront.h"
#include "scene/render_settings.h"
#include "scene/scene.h"

namespace test_file_render_identity {  // keeps this file's helpers apart in a unity batch

using namespace montecl;
using namespace montecl_test;  // runMontecl, TempDir
namespace fs = std::filesystem;

namespace {

// A valid value of the row other than the one in r.
SettingValue otherValue(const RenderSetting& s, const RenderSettings& r) {
  const SettingValue now = s.get(r);
  switch (s.rule.kind) {
    case SettingRule::Integer:
      for (long long v : {s.rule.lo, s.rule.lo + 1, s.rule.lo + 2, s.rule.hi})
        if (v != std::get<long long>(now) && (v != 0 || s.rule.zeroAllowed) && v <= s.rule.hi) return v;
      break;
    case SettingRule::Number: return std::get<float>(now) * 0.5f;
    case SettingRule::Choice:
      for (const std::string& n : s.rule.names)
        if (n != std::get<std::string>(now)) return n;
      break;
    case SettingRule::Colour: return glm::vec3(1.0f, 2.0f, 3.0f);
    case SettingRule::Bool: return !std::get<bool>(now);
    case SettingRule::Filter: return std::string(std::get<std::string>(now) == "gaussian" ? "triangle" : "gaussian");
  }
  FAIL("no other value for " << s.key);
  return now;
}

// The rows that are not in the settings string, each with why the identity needs no more of it.
const std::map<std::string, std::string> kOutsideSettingsString = {
    {"spp", "the sample range: the provenance's samples and the key's spp"},
    {"seed", "the sample range: the provenance's samples and the checkpoint's seed"},
    {"denoise", "adds denoised layers; the estimate is the same"},
    {"denoise_quality", "adds denoised layers; the estimate is the same"},
    {"missing_textures", "where both succeed, error and warn render the same image"},
};

}  // namespace

TEST_CASE("identity: every row of the settings table changes the render key, or is named with its reason" *
          doctest::test_suite("cpu")) {
  Scene scene;
  RenderOptions options;
  for (const RenderSetting& s : renderSettings()) {
    INFO("render." << s.key);
    RenderSettings base;
    // An integrator the row changes (the integrator row itself changes them all).
    for (int i = 0; i < 3; ++i)
      if (s.integrators & integratorBit(Integrator(i))) {
        base.integrator = Integrator(i);
        break;
      }
    // render.filter is recorded only when it is not the default box (renders from before filters
    // existed keep their key): from a triangle filter the row takes part.
    if (s.key == "filter") base.filter.type = FilterType::Triangle;
    // The sub-sequence count is recorded only where the error estimate makes them.
    if (s.key == "sobol_splits") base.errorEstimate = true;
    // render.adaptive is recorded only when on (plain renders keep their key): from on, the row
    // takes part (turned off, the key changes).
    if (s.key == "adaptive") base.adaptive = true;
    REQUIRE((!s.applies || s.applies(base)));
    RenderSettings changed = base;
    s.set(changed, otherValue(s, base));
    scene.render = base;
    const std::uint64_t before = renderKey(scene, options);
    const CheckpointInfo infoBefore = checkpointInfo(scene, options);
    scene.render = changed;
    const std::uint64_t after = renderKey(scene, options);
    const CheckpointInfo infoAfter = checkpointInfo(scene, options);
    if (s.provenance) {
      CHECK(integratorSettings(base) != integratorSettings(changed));
      CHECK(before != after);
      continue;
    }
    const auto why = kOutsideSettingsString.find(s.key);
    REQUIRE_MESSAGE(why != kOutsideSettingsString.end(),
                    "a row outside the provenance must be named in kOutsideSettingsString with its reason");
    CHECK(integratorSettings(base) == integratorSettings(changed));
    if (s.key == "spp") CHECK(before != after);
    if (s.key == "seed") CHECK(infoBefore.seed != infoAfter.seed);
  }
  // What is outside the table: the texture budget's effect.
  scene.render = RenderSettings();
  const std::uint64_t plain = renderKey(scene, options);
  options.identityExtra = "texture_levels_dropped=1";
  CHECK(renderKey(scene, options) != plain);
}

// Every option of `montecl render` is a row of the table (above) or classed here: in the identity
// some other way, or unable to change a pixel. A new option must be added to one of the two.
TEST_CASE("identity: every render option outside the settings table is classed as identity or not" *
          doctest::test_suite("cli sanitize")) {
  const std::set<std::string> inIdentity = {
      "--width", "--height",                    // the image size, compared by resume and merge
      "--env", "--env-scale", "--env-rotate",   // the scene digest's environment
      "--view", "--camera", "--look-from", "--look-at", "--fov",  // the scene digest's camera
      "--scene",                                // the scene digest's triangles (a glTF file's scenes[N])
      "--first-sample", "--target-error", "--min-spp", "--max-spp", "--aov",  // sample ranges and the key
      "--texture-budget",                       // the levels it drops (texture_levels_dropped)
  };
  const std::set<std::string> noPixel = {
      "--output", "--overwrite", "--device", "--wave-size", "--work-group-size", "--lanes", "--no-fuse",
      "--split-budget", "--bvh-layout", "--time", "--quiet", "--verbose", "--profile", "--help",
      "--checkpoint", "--checkpoint-every", "--resume", "--mpi-ranks", "--memory-limit"};
  std::set<std::string> tableOptions;
  for (const RenderSetting& s : renderSettings())
    if (!s.option.empty()) tableOptions.insert(s.option);
  CliResult r = runMontecl({"render", "--help"});
  REQUIRE(r.exitCode == 0);
  std::istringstream lines(r.out);
  std::string line;
  int seen = 0;
  while (std::getline(lines, line)) {
    const std::size_t at = line.find("--");
    if (at == std::string::npos || line.find_first_not_of(' ') != line.find('-')) continue;
    std::string option = line.substr(at);
    option = option.substr(0, option.find_first_of(" ,="));
    if (option.size() < 3) continue;
    ++seen;
    INFO(option);
    CHECK((tableOptions.count(option) + inIdentity.count(option) + noPixel.count(option)) == 1);
  }
  CHECK(seen > 20);
}

TEST_CASE("identity: --resume and merge refuse a render whose --texture-budget dropped other mip levels" *
          doctest::test_suite("cli sanitize")) {
  TempDir dir;
  dir.write("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 4 0\nvt 4 4\nvt 0 4\nf 1/1 2/2 3/3 4/4\n");
  std::vector<float> texels(64 * 64 * 3);
  for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = float((i * 7919) % 101) / 100.0f;
  writeRgbImage(dir.file("tex.png"), 64, 64, texels);
  dir.write("scene.json", R"({"camera": {"position": [0, 0, 3], "target": [0, 0, 0], "fov_y": 45, "width": 8, "height": 8},
    "meshes": [{"file": "quad.obj", "material": {"albedo_texture": "tex.png"}}],
    "render": {"integrator": "direct", "spp": 4}, "environment": {"radiance": [1, 1, 1]}})");
  const std::string scene = dir.file("scene.json"), ckpt = dir.file("a.ckpt");
  auto render = [&](const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> args{"render", scene, "-o", dir.file(out), "-q", "--device", "host", "--wave-size", "16"};
    args.insert(args.end(), extra.begin(), extra.end());
    return runMontecl(args);
  };
  // 36,700 bytes: the finest level (32 KiB of half-float texels) fits, the whole chain (43 KiB)
  // does not, so the finest level is dropped.
  const std::vector<std::string> small = {"--texture-budget", "0.035"};
  CliResult a = render("a.exr", {"--checkpoint", ckpt, "--checkpoint-every", "0.000001"});
  REQUIRE_MESSAGE(a.exitCode == 0, a.err);
  // A budget that drops nothing is the same render.
  CliResult same = render("same.exr", {"--resume", ckpt, "--texture-budget", "64"});
  CHECK_MESSAGE(same.exitCode == 0, same.err);
  std::vector<std::string> resume = small;
  resume.insert(resume.end(), {"--resume", ckpt});
  CliResult r = render("b.exr", resume);
  INFO(r.err);
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("checkpoint of another render") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.file("b.exr")));
  std::vector<std::string> part = small;
  part.insert(part.end(), {"--first-sample", "4"});
  CliResult c = render("c.exr", part);
  REQUIRE_MESSAGE(c.exitCode == 0, c.err);
  CliResult m = runMontecl({"merge", dir.file("a.exr"), dir.file("c.exr"), "-o", dir.file("m.exr")});
  INFO(m.err);
  CHECK(m.exitCode == 2);
  CHECK(m.err.find("texture_levels_dropped") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.file("m.exr")));
}

}  // namespace test_file_render_identity
