// light_kinds.h: every light kind, declared once (an X-macro table, like material_kinds.h). Reads
// and writes nothing. From this table come the tags MCL_LIGHT_<kind> and the dispatch of
// kernels/stages/direct_light.h: light selection for next-event estimation, and one switch per
// interface function calling the kind's file kernels/shared/light_<kind>.h:
//   <kind>_light_probability(f)                   share of light samples that go to this kind
//   <kind>_light_sample(f, ls, origin, u0, u1, u2) a direction toward the kind's light, its
//                                                 radiance and pdf (pdf within the kind)
//   <kind>_light_pdf(f, ls, hit)                  pdf within the kind of reaching `hit`
//   <kind>_light_eval(f, ls, hit)                 radiance arriving from `hit`
// Light selection walks the table in order: a sample with u0 in [sum of the earlier kinds'
// probabilities, + this kind's) goes to this kind (u0 rescaled to [0, 1) within its share).
// Each kind's share is FrameParams share<Kind>, proportional to the kind's power (the host's
// light_table.cpp); a scene with one kind of light gives it exactly 1.
// Adding a kind: docs/adding-kinds.md.
#pragma once

#define MCL_LIGHT_KINDS(LIGHT)                                                                     \
  LIGHT(environment) /* constant or latitude-longitude map, seen by rays that escape */           \
  LIGHT(area)        /* emitting triangles, picked by power, a uniform point on one */         \
  LIGHT(point)       /* isotropic points (W/sr); delta */                                     \
  LIGHT(spot)        /* points with Mitsuba 3's spot falloff; delta */                        \
  LIGHT(directional) /* one direction from infinitely far away (W/m^2); delta */                \
  LIGHT(sun)         /* a distant disk (W/m^2 in all), sampled by solid angle; NEE only */

#define MCL_LIGHT_KIND_TAG(kind) MCL_LIGHT_##kind,
enum { MCL_LIGHT_KINDS(MCL_LIGHT_KIND_TAG) MCL_LIGHT_KIND_COUNT };
#undef MCL_LIGHT_KIND_TAG
