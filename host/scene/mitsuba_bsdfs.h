// mitsuba_bsdfs.h: Mitsuba BSDF plugins as montecl materials: diffuse, dielectric,
// roughdielectric, thindielectric, conductor, roughconductor, plastic and roughplastic (nearest
// kind, warned), and the wrappers twosided, mask (a cut-out) and bumpmap. Reads <bsdf> elements;
// writes a MaterialDesc (emission is the shape's, set by the caller).
#pragma once
#include "scene/mitsuba_textures.h"

namespace montecl {

struct MiMaterial {
  MaterialDesc desc;
  bool invisible = false;  // a mask of constant opacity below montecl's cutoff: the shape is left out
  bool twoSided = false;   // under a `twosided` (montecl's surfaces are two-sided either way)
};

MiMaterial miBsdf(MiContext& c, const MiElem& bsdf);

// A named index of refraction of Mitsuba's list ("bk7", "water", ...); false for another name.
bool miNamedIor(const std::string& name, double& ior);

}  // namespace montecl
