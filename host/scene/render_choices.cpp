// render_choices.cpp: the names of the render settings' choices (see render_choices.h).
#include "scene/render_choices.h"

namespace montecl {

const ChoiceNames<Integrator>& integratorNames() {
  static const ChoiceNames<Integrator> names{{"ao", Integrator::Ao}, {"direct", Integrator::Direct},
                                                    {"path", Integrator::Path}};
  return names;
}

const ChoiceNames<AoSampling>& aoSamplingNames() {
  static const ChoiceNames<AoSampling> names{{"uniform", AoSampling::Uniform}, {"cosine", AoSampling::Cosine}};
  return names;
}

const ChoiceNames<DirectSampling>& directSamplingNames() {
  static const ChoiceNames<DirectSampling> names{
      {"light", DirectSampling::Light}, {"brdf", DirectSampling::Brdf}, {"mis", DirectSampling::Mis}};
  return names;
}

const ChoiceNames<Sampler>& samplerNames() {
  static const ChoiceNames<Sampler> names{{"independent", Sampler::Independent}, {"sobol", Sampler::Sobol}};
  return names;
}

const ChoiceNames<DenoiseQuality>& denoiseQualityNames() {
  static const ChoiceNames<DenoiseQuality> names{
      {"fast", DenoiseQuality::Fast}, {"balanced", DenoiseQuality::Balanced}, {"high", DenoiseQuality::High}};
  return names;
}

const ChoiceNames<MissingTextures>& missingTexturesNames() {
  static const ChoiceNames<MissingTextures> names{{"error", MissingTextures::Error}, {"warn", MissingTextures::Warn}};
  return names;
}

}  // namespace montecl
