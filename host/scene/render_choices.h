// render_choices.h: the render settings that are choices (integrator, AO sampling, direct-lighting
// strategy, sampler, denoiser quality, missing textures) as enums, and their names, once: the scene file and the CLI parse them here, messages
// and tools print them from here. Reads and writes nothing.
#pragma once
#include <cstdint>
#include <map>
#include <string>

namespace montecl {

enum class Integrator : std::uint32_t { Ao, Direct, Path };
enum class AoSampling : std::uint32_t { Uniform, Cosine };
enum class DirectSampling : std::uint32_t { Light, Brdf, Mis };
enum class Sampler : std::uint32_t { Independent, Sobol };
enum class DenoiseQuality : unsigned { Fast, Balanced, High };  // Open Image Denoise's quality modes
enum class MissingTextures : unsigned { Error, Warn };  // a texture file that cannot be opened

// Name -> value, in the spelling of the scene file and the CLI.
template <class E>
using ChoiceNames = std::map<std::string, E>;
const ChoiceNames<Integrator>& integratorNames();     // "ao", "direct", "path"
const ChoiceNames<AoSampling>& aoSamplingNames();     // "uniform", "cosine"
const ChoiceNames<DirectSampling>& directSamplingNames();  // "light", "brdf", "mis"
const ChoiceNames<Sampler>& samplerNames();                // "independent", "sobol"
const ChoiceNames<DenoiseQuality>& denoiseQualityNames();  // "fast", "balanced", "high"
const ChoiceNames<MissingTextures>& missingTexturesNames();  // "error", "warn"

// The name of a value ("?" for a value not in the map).
template <class E>
std::string choiceName(const ChoiceNames<E>& names, E value) {
  for (const auto& [name, v] : names)
    if (v == value) return name;
  return "?";
}
inline std::string choiceName(Integrator v) { return choiceName(integratorNames(), v); }
inline std::string choiceName(AoSampling v) { return choiceName(aoSamplingNames(), v); }
inline std::string choiceName(DirectSampling v) { return choiceName(directSamplingNames(), v); }

// "\"a\", \"b\"" (quoted, for messages) or "a | b" (for help texts).
template <class E>
std::string choiceList(const ChoiceNames<E>& names, bool quoted) {
  std::string list;
  for (const auto& entry : names) {
    if (!list.empty()) list += quoted ? ", " : " | ";
    list += quoted ? "\"" + entry.first + "\"" : entry.first;
  }
  return list;
}

}  // namespace montecl
