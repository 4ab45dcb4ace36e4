// render_settings.h: the render settings (the scene file's "render" block, the CLI's overrides),
// declared once as a table: key, CLI option, type, default, valid values, help, and which
// integrators read each. The scene-file parser, the CLI options and their validation, the
// provenance string and the settings table of docs/scene-format.md (`montecl settings
// --markdown`) all come from it, so a new setting is one row in render_settings.cpp plus its
// member here and its use. Reads and writes nothing.
#pragma once
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <algorithm>
#include <variant>
#include <vector>

#include "scene/json_fields.h"
#include "scene/pixel_filter.h"
#include "scene/render_choices.h"

namespace montecl {

// Limits shared by scene files and the command line (one rule for both).
constexpr int kMaxImageSide = 16384;    // camera.width / camera.height, --width / --height
constexpr int kMaxLightSamples = 1024;  // render.light_samples, --light-samples

struct RenderSettings {
  Integrator integrator = Integrator::Ao;
  int spp = 64;
  std::uint32_t seed = 0;
  float aoDistance = 1e30f;         // occluders farther than this do not count
  AoSampling aoSampling = AoSampling::Cosine;
  glm::vec3 background{0.0f};
  DirectSampling directSampling = DirectSampling::Mis;  // (integrator direct)
  int lightSamples = 1;                // light samples per shading point (integrators "direct", "path")
  int maxDepth = -1;  // integrator "path", Mitsuba's convention: -1 unlimited, 1 emitters seen, 2 direct, ...
  int rrDepth = 5;    // integrator "path": Russian roulette from this path depth on (>= 1)
  Sampler sampler = Sampler::Sobol;  // where the uniform numbers come from (shared/sampler.h)
  int sobolSplits = 4;  // sobol with errorEstimate: independently scrambled sub-sequences per pixel
  // sobol: split each pixel's samples into sobolSplits sub-sequences for an honest error of the mean.
  // Off by default because the split costs about 3x in MSE against one sequence; adaptive
  // sampling turns it on (the CLI's --target-error), since it stops pixels on that estimate.
  bool errorEstimate = false;
  // Adaptive sampling under a budget (--spp N as the average, and --time): after a first pass the
  // remaining samples go to pixels by their estimated relative error (render/adaptive_budget.h).
  bool adaptive = false;
  bool denoise = false;  // Open Image Denoise on the final image (image/oidn_denoiser.h)
  DenoiseQuality denoiseQuality = DenoiseQuality::High;  // OIDN's own default
  MissingTextures missingTextures = MissingTextures::Error;  // what a texture file that cannot be opened does
  PixelFilter filter;  // the pixel filter the camera rays' offsets are drawn from (box 0.5: the pixel)
};

// Whether render.error_estimate applies (the sobol sampler only) and whether render.sobol_splits
// does (sobol with the error estimate asked for), and the sub-sequences a render splits each
// pixel's samples into (sobol_splits then, else 1: one Owen-scrambled sequence, the lowest error):
// the one place of that rule, asked by FrameParams, the wave shape and the provenance string.
inline bool errorEstimateApplies(const RenderSettings& r) { return r.sampler == Sampler::Sobol; }
inline bool sobolSplitsApply(const RenderSettings& r) { return errorEstimateApplies(r) && r.errorEstimate; }
inline int sobolSplitsUsed(const RenderSettings& r) { return sobolSplitsApply(r) ? std::max(1, r.sobolSplits) : 1; }

// A setting's value: an integer, a number, a choice's name, a colour or a switch.
using SettingValue = std::variant<long long, float, std::string, glm::vec3, bool>;

// What values a setting takes.
struct SettingRule {
  enum Kind { Integer, Number, Choice, Colour, Bool, Filter } kind = Integer;  // Bool: a flag on the command line;
                                                                     // Filter: pixel_filter.h's text
  long long lo = 0, hi = 0;         // Integer: within [lo, hi] ...
  bool zeroAllowed = true;          // ... and not 0 unless this
  std::vector<std::string> names;   // Choice: the accepted names
  float colourMax = 3.4028235e38f;  // Colour: each component at most this
  std::string text;                 // the rule in words: "a positive integer up to 1024"
};

// Bit per integrator (1 << Integrator) in RenderSetting::integrators.
constexpr unsigned kEveryIntegrator = ~0u;
constexpr unsigned integratorBit(Integrator i) { return 1u << unsigned(i); }

struct RenderSetting {
  std::string key;     // render.<key> in a scene file
  std::string option;  // montecl render --<option>; empty: scene file only
  std::string help;    // what it does (CLI help and docs)
  SettingRule rule;
  // The integrators whose result it changes, and whether the provenance string records it (spp
  // and seed are recorded as the sample ranges instead).
  unsigned integrators = kEveryIntegrator;
  bool provenance = true;
  std::function<void(RenderSettings&, const SettingValue&)> set;
  std::function<SettingValue(const RenderSettings&)> get;
  // Whether the setting takes part in a render with these settings beyond its integrators (e.g.
  // sobol_splits under the sobol sampler only); empty: always. The provenance string asks it.
  std::function<bool(const RenderSettings&)> applies;
};

// Every setting, in the order the docs and the provenance string list them.
const std::vector<RenderSetting>& renderSettings();

// Reads the scene file's "render" object (unknown keys warned); throws "<file>: render.<key>: ...".
RenderSettings parseRenderSettings(const JsonCtx& ctx, const nlohmann::json& render);
// Checks a CLI text against a setting's rule: "" when it is valid, else "must be <rule>, got '<text>'".
std::string settingTextProblem(const RenderSetting& s, const std::string& text);
// Sets a setting from a CLI text that settingTextProblem accepted.
void setFromText(const RenderSetting& s, const std::string& text, RenderSettings& r);
// The value as the provenance string and the docs print it ("1e+30", "mis", "0,0,0").
std::string settingValueText(const SettingValue& v);
// "integrator=direct direct_sampling=mis light_samples=1 background=0,0,0": the settings that
// change this render's result (provenance: renders merge only when these agree).
std::string integratorSettings(const RenderSettings& r);
// The markdown table of docs/scene-format.md: | key | type | default | valid | meaning |.
std::string renderSettingsMarkdown();

}  // namespace montecl
