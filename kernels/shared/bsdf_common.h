// bsdf_common.h: what every material kind's BSDF file (bsdf_<kind>.h) returns and uses: the sample
// structs of the BSDF interface and local coordinates around a normal. Pure; compiled by the
// kernels and by the host tests.
// Conventions of the interface (shared/bsdf.h): wo points from the surface toward the viewer, wi
// toward the light, both unit; directions are taken around a shading frame (shared/shading.h).
#pragma once
#include "lights.h"
#include "sampling.h"
#include "shading.h"

// A direction drawn by <kind>_sample with its weight.
typedef struct {
  float3 wi;
  float3 weight;  // f * cos / pdf
  float pdf;      // solid angle; 0: no direction (the sample is absorbed)
} BsdfSample;

// The direct integrator draws its BSDF direction in shade_direct and weighs it in
// shade_direct_hit, with only the direction passed between them: <kind>_sample_direction gives
// the direction (traced 0: absorbed, no ray), <kind>_direction_weight the f cos / p of that
// direction (counts 0: it contributes nothing, the slot stays 0). For a kind whose sample weight
// is simply eval / pdf the pair is sample().wi with pdf > 0, and eval * (1 / pdf) with pdf > 0.
typedef struct {
  float3 wi;
  int traced;
} BsdfDirection;

typedef struct {
  float3 weight;  // f * cos / pdf
  int counts;
} BsdfWeight;

// Local coordinates of w in the frame (t, b, n) of make_basis.
MCL_INLINE float3 to_local(float3 w, float3 n) {
  float3 t, b;
  make_basis(n, &t, &b);
  return make_float3(dot(w, t), dot(w, b), dot(w, n));
}
