// material_kinds.h: every material kind, declared once (an X-macro table, as stage_table.h
// declares the stages). Reads and writes nothing; needs no other header, so the host's scene code
// (MaterialDesc, the loaders) and the kernels (Material, shared/bsdf.h's dispatch) share it.
// From this table come:
// - the kind tags MCL_MATERIAL_<kind> (0, 1, ... in table order) that Material::alpha.w holds as
//   uint bits and MaterialDesc::kind holds on the host;
// - the BSDF dispatch of shared/bsdf.h: one switch per interface function, case <kind> calling
//   <kind>_f / _eval / _pdf / _sample / _direction_weight / _albedo of the
//   kind's file kernels/shared/bsdf_<kind>.h, and the parameter union BsdfParams (member <kind>
//   of type <Params>);
// - on the host, the names a scene file's material "type" accepts (materialKindFromName).
// Adding a kind: docs/adding-kinds.md.
#pragma once

// KIND(kind, Params): Params is the struct of the kind's BSDF parameters at a hit (bsdf_<kind>.h).
// The first row is the default: a zero tag (a Material{} filled with zeros, and every material
// before kinds existed) is that kind.
#define MCL_MATERIAL_KINDS(KIND)                                                                   \
  KIND(diffuse, DiffuseBsdf) /* Lambert Kd (x albedo texture) + optional GGX glossy lobe Ks */    \
  KIND(conductor, ConductorBsdf) /* metal: complex IOR eta + i k; mirror, GGX or Beckmann */      \
  KIND(dielectric, DielectricBsdf) /* smooth glass of index ior: delta reflection + refraction */   \
  KIND(thin_dielectric, ThinDielectricBsdf) /* thin sheet: delta reflection + straight through */   \
  KIND(metal_rough, MetalRoughBsdf) /* glTF metallic-roughness: Lambert + Schlick GGX */          \
  KIND(coated_diffuse, CoatedDiffuseBsdf) /* dielectric coat over Lambert, random walk between */ \
  KIND(coated_conductor, CoatedConductorBsdf) /* dielectric coat over a GGX metal, random walk */

#define MCL_MATERIAL_KIND_TAG(kind, Params) MCL_MATERIAL_##kind,
enum { MCL_MATERIAL_KINDS(MCL_MATERIAL_KIND_TAG) MCL_MATERIAL_KIND_COUNT };
#undef MCL_MATERIAL_KIND_TAG

#if !defined(__OPENCL_C_VERSION__) && !defined(__OPENCL_VERSION__)
#include <cstdint>
#include <cstring>

// A kind's name as scene files spell it ("diffuse"); nullptr for a tag outside the table.
inline const char* materialKindName(std::uint32_t kind) {
#define MCL_MATERIAL_KIND_NAME(kind_, Params) \
  if (kind == MCL_MATERIAL_##kind_) return #kind_;
  MCL_MATERIAL_KINDS(MCL_MATERIAL_KIND_NAME)
#undef MCL_MATERIAL_KIND_NAME
  return nullptr;
}

// The tag of the kind named `name`; false when no kind has that name.
inline bool materialKindFromName(const char* name, std::uint32_t& kind) {
#define MCL_MATERIAL_KIND_FIND(kind_, Params)        \
  if (std::strcmp(name, #kind_) == 0) {              \
    kind = MCL_MATERIAL_##kind_;                     \
    return true;                                     \
  }
  MCL_MATERIAL_KINDS(MCL_MATERIAL_KIND_FIND)
#undef MCL_MATERIAL_KIND_FIND
  return false;
}

// "diffuse, ..." : every kind's name, for error messages.
inline const char* materialKindNames() {
#define MCL_MATERIAL_KIND_LIST(kind_, Params) ", " #kind_
  return &(MCL_MATERIAL_KINDS(MCL_MATERIAL_KIND_LIST))[2];
#undef MCL_MATERIAL_KIND_LIST
}
#endif
