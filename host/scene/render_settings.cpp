// render_settings.cpp: the render settings table (render_settings.h) and what reads it: the scene
// file's "render" block, CLI texts, the provenance string and the docs' table.
#include "scene/render_settings.h"

#include <cerrno>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "scene/load_util.h"

namespace montecl {
namespace {

template <class E>
SettingRule choiceRule(const ChoiceNames<E>& names) {
  SettingRule r;
  r.kind = SettingRule::Choice;
  for (const auto& entry : names) r.names.push_back(entry.first);
  r.text = choiceList(names, /*quoted=*/false);
  return r;
}

SettingRule integerRule(long long lo, long long hi, std::string text, bool zeroAllowed = true) {
  SettingRule r;
  r.kind = SettingRule::Integer;
  r.lo = lo, r.hi = hi, r.zeroAllowed = zeroAllowed, r.text = std::move(text);
  return r;
}

SettingRule numberRule() {  // finite, > 0 and at most FLT_MAX (a float setting)
  SettingRule r;
  r.kind = SettingRule::Number;
  r.text = "a positive number";
  return r;
}

SettingRule boolRule() {  // a JSON true/false; on the command line a flag
  SettingRule r;
  r.kind = SettingRule::Bool;
  r.text = "true or false";
  return r;
}

SettingRule filterRule() {
  SettingRule r;
  r.kind = SettingRule::Filter;
  r.text = std::string("a filter: ") + filterTypeNames() + ", optionally with ,radius=R and its parameters";
  return r;
}

// The pixel filter, as its text form (pixel_filter.h); recorded in the provenance only when it is
// not the default box, so renders from before filters existed still merge with today's.
RenderSetting filterRow() {
  RenderSetting s{"filter", "--filter",
                  "Pixel filter, importance sampled (each camera ray's offset drawn from it, weight 1): box (radius "
                  "0.5: the pixel), triangle, gaussian (sigma), mitchell (b, c), lanczos (tau), their negative lobes "
                  "clamped to 0; e.g. gaussian,radius=1.5,sigma=0.5",
                  filterRule(), kEveryIntegrator, true, {}, {},
                  [](const RenderSettings& r) { return !(r.filter == PixelFilter{}); }};
  s.set = [](RenderSettings& r, const SettingValue& v) {
    std::string problem;
    parseFilterText(std::get<std::string>(v), r.filter, &problem);
  };
  s.get = [](const RenderSettings& r) { return SettingValue(filterText(r.filter)); };
  return s;
}

SettingRule colourRule() {
  SettingRule r;
  r.kind = SettingRule::Colour;
  r.text = "3 numbers >= 0";
  return r;
}

// The background is seen by whole pixels: past this a sample's square overflows the EXR's float
// variance (1e30 failed only when the image was written); 65504, the largest half float, leaves
// room for any camera ray count and is far above any sky.
SettingRule backgroundRule() {
  SettingRule r = colourRule();
  r.colourMax = 65504.0f;
  r.text = "3 numbers in [0, 65504]";
  return r;
}

// A row whose value is the member `m` of type T (int / uint32_t / float / vec3, or a choice enum
// through its names).
template <class T>
RenderSetting row(const char* key, const char* option, const char* help, SettingRule rule, T RenderSettings::*m,
                  unsigned integrators = kEveryIntegrator, bool provenance = true,
                  std::function<bool(const RenderSettings&)> applies = {}) {
  RenderSetting s{key, option, help, std::move(rule), integrators, provenance, {}, {}, std::move(applies)};
  if constexpr (std::is_same_v<T, float>) {
    s.set = [m](RenderSettings& r, const SettingValue& v) { r.*m = std::get<float>(v); };
    s.get = [m](const RenderSettings& r) { return SettingValue(r.*m); };
  } else if constexpr (std::is_same_v<T, bool>) {
    s.set = [m](RenderSettings& r, const SettingValue& v) { r.*m = std::get<bool>(v); };
    s.get = [m](const RenderSettings& r) { return SettingValue(r.*m); };
  } else if constexpr (std::is_same_v<T, glm::vec3>) {
    s.set = [m](RenderSettings& r, const SettingValue& v) { r.*m = std::get<glm::vec3>(v); };
    s.get = [m](const RenderSettings& r) { return SettingValue(r.*m); };
  } else {
    s.set = [m](RenderSettings& r, const SettingValue& v) { r.*m = T(std::get<long long>(v)); };
    s.get = [m](const RenderSettings& r) { return SettingValue((long long)(r.*m)); };
  }
  return s;
}

template <class E>
RenderSetting choiceRow(const char* key, const char* option, const char* help, const ChoiceNames<E>& names,
                        E RenderSettings::*m, unsigned integrators = kEveryIntegrator, bool provenance = true) {
  RenderSetting s{key, option, help, choiceRule(names), integrators, provenance, {}, {}, {}};
  s.set = [m, &names](RenderSettings& r, const SettingValue& v) { r.*m = names.at(std::get<std::string>(v)); };
  s.get = [m, &names](const RenderSettings& r) { return SettingValue(choiceName(names, r.*m)); };
  return s;
}

std::vector<RenderSetting> makeTable() {
  const unsigned ao = integratorBit(Integrator::Ao), direct = integratorBit(Integrator::Direct),
                 path = integratorBit(Integrator::Path);
  const long long intMax = INT_MAX;
  const std::string lightRule = "a positive integer up to " + std::to_string(kMaxLightSamples);
  return {
      choiceRow("integrator", "--integrator",
                "The estimator: ao (ambient occlusion), direct (direct lighting from area lights and the "
                "environment) or path (path tracing with next-event estimation)",
                integratorNames(), &RenderSettings::integrator),
      row("spp", "--spp", "Samples per pixel", integerRule(1, intMax, "a positive integer"), &RenderSettings::spp,
          kEveryIntegrator, false),
      row("seed", "--seed", "Random seed: every random number is a function of (seed, pixel, sample, dimension)",
          integerRule(0, 0xffffffffLL, "an integer in [0, 4294967295]"), &RenderSettings::seed, kEveryIntegrator,
          false),
      choiceRow("ao_sampling", "--ao-sampling", "AO directions: uniform over the hemisphere or cosine-weighted",
                aoSamplingNames(), &RenderSettings::aoSampling, ao),
      row("ao_distance", "--ao-distance", "AO: occluders farther than this are ignored", numberRule(),
          &RenderSettings::aoDistance, ao),
      choiceRow("direct_sampling", "--direct-sampling",
                "Direct lighting: light sampling, BRDF sampling, or both combined by MIS (power heuristic)",
                directSamplingNames(), &RenderSettings::directSampling, direct),
      row("light_samples", "--light-samples", "Light samples per shading point (direct, path)",
          integerRule(1, kMaxLightSamples, lightRule), &RenderSettings::lightSamples, direct | path),
      row("max_depth", "--max-depth",
          "Path: longest path in segments, Mitsuba's convention: -1 unlimited, 1 emitters seen directly, 2 direct "
          "lighting, 3 one indirect bounce, ...",
          integerRule(-1, intMax, "-1 (unlimited) or a positive integer", /*zeroAllowed=*/false),
          &RenderSettings::maxDepth, path),
      row("rr_depth", "--rr-depth", "Path: Russian roulette from this path depth on",
          integerRule(1, intMax, "a positive integer"), &RenderSettings::rrDepth, path),
      choiceRow("sampler", "--sampler",
                "Where the uniform numbers come from: independent (a hash per sample and dimension) or "
                "sobol (Owen-scrambled Sobol points, stratified; with error_estimate the error figures come "
                "from the spread of sobol_splits sub-sequences)",
                samplerNames(), &RenderSettings::sampler),
      row("sobol_splits", "--sobol-splits",
          "With sobol and error_estimate: independently scrambled sub-sequences per pixel (sample s in s mod K); "
          "the error of the mean comes from the spread of their means (EXR layers split0.* ..., err.*); 1: one "
          "sequence, error figures from var.* (they overstate it)",
          integerRule(1, 64, "an integer in [1, 64]"), &RenderSettings::sobolSplits, kEveryIntegrator, true,
          sobolSplitsApply),
      row("error_estimate", "--error-estimate",
          "With sobol: split each pixel's samples into sobol_splits sub-sequences whose spread gives an honest "
          "error of the mean (EXR err.*, the adaptive stop, the converged count); on with --target-error. Off: one "
          "Owen-scrambled sequence per pixel (about 3x lower MSE), error figures from var.* (they overstate it)",
          boolRule(), &RenderSettings::errorEstimate, kEveryIntegrator, true, errorEstimateApplies),
      // In the provenance only when on, so plain renders keep their settings string (and merge
      // with earlier ones); adaptive renders merge only with adaptive ones.
      row("adaptive", "--adaptive",
          "Adaptive sampling under a budget: --min-spp samples per pixel first, then the rest of --spp (the "
          "average; with --time, until the time is up) in rounds that double the total, each pixel's share "
          "following its estimated relative error; turns error_estimate on; EXR samples holds the counts",
          boolRule(), &RenderSettings::adaptive, kEveryIntegrator, true,
          [](const RenderSettings& r) { return r.adaptive; }),
      row("background", "", "Radiance of camera rays that hit nothing (without an environment)", backgroundRule(),
          &RenderSettings::background),
      // Denoising changes only the added denoised layers, never the estimate: not in the provenance,
      // so denoised and plain renders of one scene merge.
      row("denoise", "--denoise",
          "Denoise the final image with Open Image Denoise (filter RT, albedo and normal guides; needs `bash "
          "scripts/setup.sh --oidn`): PNG/PFM get the denoised image, EXR keeps the noisy R, G, B and adds "
          "denoised.R/G/B",
          boolRule(), &RenderSettings::denoise, kEveryIntegrator, false),
      choiceRow("denoise_quality", "--denoise-quality",
                "Open Image Denoise quality mode with --denoise: fast, balanced or high (slowest, best)",
                denoiseQualityNames(), &RenderSettings::denoiseQuality, kEveryIntegrator, false),
      // Not in the provenance: where both succeed, error and warn render the same image.
      choiceRow("missing_textures", "--missing-textures",
                "Texture files that cannot be opened (in any case of their name): error lists them all and stops; "
                "warn lists them all in one warning and renders each as its material's factor (the texture left out)",
                missingTexturesNames(), &RenderSettings::missingTextures, kEveryIntegrator, false),
      filterRow(),
  };
}

std::string number(double v, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string valueText(const SettingValue& v, int digits) {
  if (const long long* i = std::get_if<long long>(&v)) return std::to_string(*i);
  if (const float* f = std::get_if<float>(&v)) return number(*f, digits);
  if (const std::string* s = std::get_if<std::string>(&v)) return *s;
  if (const bool* b = std::get_if<bool>(&v)) return *b ? "true" : "false";
  const glm::vec3& c = std::get<glm::vec3>(v);
  return number(c.x, digits) + "," + number(c.y, digits) + "," + number(c.z, digits);
}

}  // namespace

const std::vector<RenderSetting>& renderSettings() {
  static const std::vector<RenderSetting> table = makeTable();
  return table;
}

RenderSettings parseRenderSettings(const JsonCtx& ctx, const nlohmann::json& j) {
  RenderSettings r;
  requireObject(ctx, j, "render");
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool known = false;
    for (const RenderSetting& s : renderSettings()) known = known || s.key == it.key();
    if (!known)
      ctx.warnings.push_back(oneLine(ctx.file, 4096) + ": " + oneLine("render." + it.key()) + ": unknown key, ignored");
  }
  for (const RenderSetting& s : renderSettings()) {
    const nlohmann::json* v = optionalKey(j, s.key.c_str());
    if (!v) continue;
    const std::string where = "render." + s.key;
    const SettingRule& rule = s.rule;
    switch (rule.kind) {
      case SettingRule::Integer: {
        const long long i = getInteger(ctx, *v, where, rule.lo, rule.hi, rule.text.c_str());
        if (i == 0 && !rule.zeroAllowed) jsonFail(ctx, where, "must be " + rule.text + ", got 0");
        s.set(r, i);
        break;
      }
      case SettingRule::Number: {
        const float f = getFloat(ctx, *v, where);
        if (!(f > 0.0f)) jsonFail(ctx, where, "must be " + rule.text + ", got " + v->dump());
        s.set(r, f);
        break;
      }
      case SettingRule::Choice: {
        std::string list;
        for (const std::string& n : rule.names) list += (list.empty() ? "\"" : ", \"") + n + "\"";
        if (!v->is_string()) jsonFail(ctx, where, "expected one of " + list + ", got " + v->type_name());
        const std::string name = v->get<std::string>();
        bool ok = false;
        for (const std::string& n : rule.names) ok = ok || n == name;
        if (!ok) jsonFail(ctx, where, "expected one of " + list + ", got " + v->dump());
        s.set(r, name);
        break;
      }
      case SettingRule::Colour: {
        const glm::vec3 c = getColor(ctx, *v, where);
        if (c.x > rule.colourMax || c.y > rule.colourMax || c.z > rule.colourMax)
          jsonFail(ctx, where, "must be " + rule.text + ", got " + v->dump());
        s.set(r, c);
        break;
      }
      case SettingRule::Bool:
        if (!v->is_boolean()) jsonFail(ctx, where, "expected true or false, got " + v->dump());
        s.set(r, v->get<bool>());
        break;
      case SettingRule::Filter: s.set(r, filterText(filterFromJson(ctx, *v, where))); break;
    }
  }
  return r;
}

std::string settingTextProblem(const RenderSetting& s, const std::string& text) {
  const SettingRule& rule = s.rule;
  const std::string got = ", got '" + text + "'";
  switch (rule.kind) {
    case SettingRule::Integer: {
      errno = 0;
      char* end = nullptr;
      const long long v = std::strtoll(text.c_str(), &end, 10);
      const bool ok = !text.empty() && end && *end == '\0' && errno == 0 && v >= rule.lo && v <= rule.hi &&
                      (v != 0 || rule.zeroAllowed);
      return ok ? std::string() : "must be " + rule.text + got;
    }
    case SettingRule::Number: {
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      const bool number = !text.empty() && end && *end == '\0' && std::isfinite(v);
      if (number && v > double(FLT_MAX)) return "must be " + rule.text + " up to " + valueText(FLT_MAX, 6) + got;
      return number && v > 0.0 ? std::string() : "must be " + rule.text + got;
    }
    case SettingRule::Choice:
      for (const std::string& n : rule.names)
        if (n == text) return std::string();
      return "must be one of " + rule.text + got;
    case SettingRule::Colour: {
      float c[3];
      char tail = 0;
      const bool ok = std::sscanf(text.c_str(), "%f,%f,%f%c", &c[0], &c[1], &c[2], &tail) == 3 &&
                      std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]) && c[0] >= 0 && c[1] >= 0 &&
                      c[2] >= 0 && c[0] <= rule.colourMax && c[1] <= rule.colourMax && c[2] <= rule.colourMax;
      return ok ? std::string() : "must be " + rule.text + " as R,G,B" + got;
    }
    case SettingRule::Bool:
      return text == "true" || text == "false" ? std::string() : "must be " + rule.text + got;
    case SettingRule::Filter: {
      PixelFilter f;
      std::string problem;
      return parseFilterText(text, f, &problem) ? std::string() : problem;
    }
  }
  return "unknown setting kind";
}

void setFromText(const RenderSetting& s, const std::string& text, RenderSettings& r) {
  switch (s.rule.kind) {
    case SettingRule::Integer: s.set(r, std::strtoll(text.c_str(), nullptr, 10)); break;
    case SettingRule::Number: s.set(r, float(std::strtod(text.c_str(), nullptr))); break;
    case SettingRule::Choice: s.set(r, text); break;
    case SettingRule::Colour: {
      glm::vec3 c(0.0f);
      std::sscanf(text.c_str(), "%f,%f,%f", &c.x, &c.y, &c.z);
      s.set(r, c);
      break;
    }
    case SettingRule::Bool: s.set(r, text == "true"); break;
    case SettingRule::Filter: s.set(r, text); break;
  }
}

std::string settingValueText(const SettingValue& v) { return valueText(v, 9); }

std::string integratorSettings(const RenderSettings& r) {
  std::string out;
  for (const RenderSetting& s : renderSettings())
    if (s.provenance && (s.integrators & integratorBit(r.integrator)) && (!s.applies || s.applies(r)))
      out += (out.empty() ? "" : " ") + s.key + "=" + settingValueText(s.get(r));
  return out;
}

std::string renderSettingsMarkdown() {
  static const char* const types[] = {"integer", "number", "name", "[r, g, b]", "boolean", "filter"};
  std::ostringstream md;
  md << "| key | type | default | valid | meaning |\n|---|---|---|---|---|\n";
  const RenderSettings defaults;
  for (const RenderSetting& s : renderSettings()) {
    std::string valid = s.rule.text;
    if (s.rule.kind == SettingRule::Choice) {
      valid.clear();
      for (const std::string& n : s.rule.names) valid += (valid.empty() ? "`" : ", `") + n + "`";
    }
    md << "| `" << s.key << "` | " << types[s.rule.kind] << " | " << valueText(s.get(defaults), 6) << " | " << valid
       << " | " << s.help << (s.option.empty() ? " (scene file only)" : " (`" + s.option + "`)") << " |\n";
  }
  return md.str();
}

}  // namespace montecl
