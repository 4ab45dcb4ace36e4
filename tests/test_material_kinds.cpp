// test_material_kinds.cpp: every row of the material kind table (kernels/shared/material_kinds.h)
// against its BSDF (shared/bsdf.h dispatch), compiled as C++: the name round-trips, the packer
// (render/device_materials.cpp) stores the tag where bsdf_from_material finds it, and for each
// kind's test materials, around a flat and a tilted shading frame and at several viewing angles,
// eval / pdf / sample / the split sample / albedo agree: each sample's pdf and weight are pdf() and
// eval() / pdf() there, f = eval / |cos|, the split weight (direction_weight of the sample's
// direction) is sample()'s weight, the mean sample weight (the reflectance, estimated by
// importance sampling) matches an independent uniform-sphere estimate of the integral of eval
// within a z-score of their standard errors, and where a case says so, that reflectance is
// albedo() within a z-score of its own standard error. A new table row without test cases
// (kindCases_<kind>) does not compile.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "kernels/shared/bsdf.h"
#include "kernels/shared/rng.h"
#include "render/device_materials.h"
#include "stats.h"

namespace test_file_material_kinds {  // keeps this file's helpers apart in a unity batch

using montecl::MaterialDesc;
using montecl_test::RunningStats;

namespace {

struct KindCase {
  std::string what;
  MaterialDesc desc;
  float3 albedo;              // the textured albedo at the hit, handed to bsdf_from_material
  bool albedoIsReflectance;   // on a flat frame the reflectance (mean sample weight) is albedo()
  // Whether uniform directions can find every lobe: not a near-mirror GGX lobe (alpha 1e-3, a
  // smooth coat), whose reflectance they miss; such a case is checked by its sampled estimate only.
  bool uniformResolves = true;
};

MaterialDesc withKind(std::uint32_t kind, float3 kd, float3 ks, float ns) {
  MaterialDesc d;
  d.kind = kind;
  d.albedo = kd;
  d.specular = ks;
  d.specularExponent = ns;
  return d;
}

// The diffuse kind: Lambert alone (its reflectance is Kd x texture), and with glossy lobes
// (single-scattering GGX loses energy: no albedo claim, only consistency and energy <= 1).
std::vector<KindCase> kindCases_diffuse() {
  const std::uint32_t k = MCL_MATERIAL_diffuse;
  return {
      {"Lambert", withKind(k, float3(0.7f, 0.5f, 0.3f), float3(0.0f), 0.0f), float3(0.6f, 0.45f, 0.2f), true},
      {"Lambert + GGX Ns 20", withKind(k, float3(0.3f, 0.4f, 0.2f), float3(0.5f), 20.0f), float3(0.3f, 0.4f, 0.2f),
       false},
      {"Lambert + GGX Ns 0 (alpha 1)", withKind(k, float3(0.5f), float3(0.4f, 0.3f, 0.2f), 0.0f), float3(0.5f), false},
  };
}

MaterialDesc conductor(float3 eta, float3 k, float alpha) {
  MaterialDesc d;
  d.kind = MCL_MATERIAL_conductor;
  d.eta = eta, d.k = k, d.kindAlpha = alpha;
  return d;
}
MaterialDesc withIor(std::uint32_t kind, float ior) {
  MaterialDesc d;
  d.kind = kind;
  d.ior = ior;
  return d;
}
MaterialDesc metalRough(float3 base, float metallic, float roughness) {
  MaterialDesc d;
  d.kind = MCL_MATERIAL_metal_rough;
  d.albedo = base, d.metallic = metallic, d.roughness = roughness;
  return d;
}

// Metals (gold's RGB IOR), smooth (a delta mirror) and rough; no albedo claim (F(1) is the albedo
// AOV, the reflectance rises toward grazing angles).
std::vector<KindCase> kindCases_conductor() {
  const float3 eta(0.143f, 0.375f, 1.442f), k(3.983f, 2.386f, 1.603f);
  return {{"gold alpha 0.3", conductor(eta, k, 0.3f), float3(1.0f), false},
          {"gold alpha 0.05", conductor(eta, k, 0.05f), float3(1.0f), false},
          {"mirror (delta)", conductor(eta, k, 0.0f), float3(1.0f), false}};
}
std::vector<KindCase> kindCases_dielectric() {
  // From the front (outside): weights F x 1 + (1 - F) x 1 / 1.5^2 <= 1 (the other side, whose
  // refraction weight exceeds 1, is test_bsdf_kinds.cpp's).
  // Rough (alpha > 0, GGX): weights F G1(wi) + (1 - F) G1(wi) / eta^2 from the front, also <= 1.
  MaterialDesc rough = withIor(MCL_MATERIAL_dielectric, 1.5f), roughWater = withIor(MCL_MATERIAL_dielectric, 1.33f);
  rough.kindAlpha = 0.3f;
  roughWater.kindAlpha = 0.1f;
  return {{"glass 1.5", withIor(MCL_MATERIAL_dielectric, 1.5f), float3(1.0f), false},
          {"glass 1.33", withIor(MCL_MATERIAL_dielectric, 1.33f), float3(1.0f), false},
          {"rough glass 1.5 alpha 0.3", rough, float3(1.0f), false},
          {"rough glass 1.33 alpha 0.1", roughWater, float3(1.0f), false}};
}
std::vector<KindCase> kindCases_thin_dielectric() {
  return {{"sheet 1.5", withIor(MCL_MATERIAL_thin_dielectric, 1.5f), float3(1.0f), false}};
}
MaterialDesc clearcoat(MaterialDesc d, float coat, float roughness) {
  d.clearcoat = coat, d.clearcoatRoughness = roughness;
  return d;
}
MaterialDesc sheen(MaterialDesc d, float3 color, float roughness) {
  d.sheenColor = color, d.sheenRoughness = roughness;
  return d;
}
// Uncoated, and under glTF's clearcoat (KHR_materials_clearcoat: the coat's lobe picked by its
// weight, so the mixture pdf must still agree with the samples); a smooth coat is a near-mirror lobe.
// Under glTF's sheen (KHR_materials_sheen: the Charlie lobe picked by its weight and sampled by a
// cosine lobe), alone and under a coat.
std::vector<KindCase> kindCases_metal_rough() {
  return {{"dielectric rough", metalRough(float3(0.8f, 0.4f, 0.2f), 0.0f, 0.6f), float3(0.8f, 0.4f, 0.2f), false},
          {"metal glossy", metalRough(float3(0.9f, 0.7f, 0.3f), 1.0f, 0.3f), float3(0.9f, 0.7f, 0.3f), false},
          {"half metallic", metalRough(float3(0.5f), 0.5f, 0.8f), float3(0.5f), false},
          {"clearcoat 1 r 0.2 over red", clearcoat(metalRough(float3(0.8f, 0.1f, 0.1f), 0.0f, 0.6f), 1.0f, 0.2f),
           float3(0.8f, 0.1f, 0.1f), false},
          {"clearcoat 0.5 r 0.5 over metal", clearcoat(metalRough(float3(0.9f, 0.7f, 0.3f), 1.0f, 0.3f), 0.5f, 0.5f),
           float3(0.9f, 0.7f, 0.3f), false},
          {"smooth clearcoat over white", clearcoat(metalRough(float3(1.0f), 0.0f, 1.0f), 1.0f, 0.0f), float3(1.0f), false,
           false},
          {"sheen white r 0.5 over blue", sheen(metalRough(float3(0.1f, 0.2f, 0.8f), 0.0f, 0.7f), float3(1.0f), 0.5f),
           float3(0.1f, 0.2f, 0.8f), false},
          {"sheen red r 0.3 over metal", sheen(metalRough(float3(0.9f, 0.7f, 0.3f), 1.0f, 0.3f), float3(0.9f, 0.2f, 0.1f), 0.3f),
           float3(0.9f, 0.7f, 0.3f), false},
          {"sheen r 0.8 under clearcoat 0.6", clearcoat(sheen(metalRough(float3(0.5f), 0.0f, 0.5f), float3(0.6f, 0.6f, 0.9f), 0.8f), 0.6f, 0.4f),
           float3(0.5f), false}};
}
MaterialDesc coatedDiffuse(float3 kd, float alpha, float thickness, int maxDepth = 10) {
  MaterialDesc d;
  d.kind = MCL_MATERIAL_coated_diffuse;
  d.albedo = kd;
  d.kindAlpha = alpha;
  d.thickness = thickness;
  d.layerMaxDepth = maxDepth;
  return d;
}
// The white furnace: a white base under a smooth coat with no absorption (a layer 1e-6 thick) and
// a walk long enough that its series is whole reflects everything, so its reflectance is albedo()
// (the base's 1); the smooth coats' near-mirror lobe is beyond uniform directions.
std::vector<KindCase> kindCases_coated_diffuse() {
  return {{"smooth coat over red", coatedDiffuse(float3(0.8f, 0.3f, 0.2f), 0.0f, 0.01f), float3(0.8f, 0.3f, 0.2f), false,
           false},
          {"rough coat alpha 0.3", coatedDiffuse(float3(0.5f), 0.3f, 0.01f), float3(0.5f), false},
          {"rough coat alpha 0.1, thick", coatedDiffuse(float3(0.9f, 0.6f, 0.3f), 0.1f, 0.5f, 50), float3(0.9f, 0.6f, 0.3f),
           false},
          {"white furnace: white base, smooth coat", coatedDiffuse(float3(1.0f), 0.0f, 1e-6f, 1000), float3(1.0f), true,
           false}};
}

MaterialDesc coatedConductor(float3 eta, float3 k, float baseAlpha, float coatAlpha, float thickness, int maxDepth = 10) {
  MaterialDesc d;
  d.kind = MCL_MATERIAL_coated_conductor;
  d.eta = eta;
  d.k = k;
  d.baseAlpha = baseAlpha;
  d.kindAlpha = coatAlpha;
  d.thickness = thickness;
  d.layerMaxDepth = maxDepth;
  return d;
}
// Gold under coats; the white furnace: a perfect mirror (eta 0: F = 1 at every angle) under a
// smooth coat with no absorption reflects everything, albedo() (the metal's F(1)) = 1.
std::vector<KindCase> kindCases_coated_conductor() {
  const float3 eta(0.143f, 0.375f, 1.442f), k(3.983f, 2.386f, 1.603f);
  return {{"smooth coat over smooth gold", coatedConductor(eta, k, 0.0f, 0.0f, 0.01f), float3(1.0f), false, false},
          {"rough coat 0.3 over gold 0.2", coatedConductor(eta, k, 0.2f, 0.3f, 0.01f), float3(1.0f), false},
          {"rough coat 0.1 over gold 0.5, thick", coatedConductor(eta, k, 0.5f, 0.1f, 0.3f, 30), float3(1.0f), false},
          {"white furnace: perfect mirror, smooth coat", coatedConductor(float3(0.0f), float3(1.0f), 0.0f, 0.0f, 1e-6f, 1000),
           float3(1.0f), true, false}};
}

struct KindRow {
  const char* name;
  std::uint32_t tag;
  std::vector<KindCase> cases;
};

std::vector<KindRow> kindRows() {
  std::vector<KindRow> rows;
#define MCL_TEST_KIND_ROW(kind, Params) rows.push_back(KindRow{#kind, MCL_MATERIAL_##kind, kindCases_##kind()});
  MCL_MATERIAL_KINDS(MCL_TEST_KIND_ROW)
#undef MCL_TEST_KIND_ROW
  return rows;
}

float3 dirFromAngles(double theta, double phi) {
  return float3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
}

// Uniform on the unit sphere from u1, u2 in [0, 1): pdf 1 / (4 pi).
float3 uniformSphere(float u1, float u2) {
  const double z = 1.0 - 2.0 * u1, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * M_PI * u2;
  return float3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
}

float max_abs(float3 v) { return std::max(std::fabs(v.x), std::max(std::fabs(v.y), std::fabs(v.z))); }

bool near(float a, float b, float rel) { return std::fabs(a - b) <= rel * std::max(std::fabs(a), std::fabs(b)) + 1e-6f; }

}  // namespace

TEST_CASE("material kinds: names round-trip, tags are the table's order, the packer stores the tag" *
          doctest::test_suite("cpu")) {
  const std::vector<KindRow> rows = kindRows();
  REQUIRE(rows.size() == std::size_t(MCL_MATERIAL_KIND_COUNT));
  CHECK(MCL_MATERIAL_diffuse == 0);  // the default: zero-filled materials are diffuse
  CHECK(MaterialDesc{}.kind == std::uint32_t(MCL_MATERIAL_diffuse));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    CAPTURE(rows[i].name);
    CHECK(rows[i].tag == i);
    CHECK(std::string(materialKindName(rows[i].tag)) == rows[i].name);
    std::uint32_t tag = 99;
    CHECK(materialKindFromName(rows[i].name, tag));
    CHECK(tag == rows[i].tag);
    CHECK(std::string(materialKindNames()).find(rows[i].name) != std::string::npos);
    for (const KindCase& c : rows[i].cases) {
      const Material m = montecl::deviceMaterial(c.desc);
      CHECK(material_kind(m) == rows[i].tag);
      CHECK(bsdf_from_material(m, c.albedo).kind == rows[i].tag);
    }
  }
  std::uint32_t tag = 7;
  CHECK_FALSE(materialKindFromName("glass", tag));
  CHECK(tag == 7);
  CHECK(materialKindName(MCL_MATERIAL_KIND_COUNT) == nullptr);
}

TEST_CASE("material kinds: every kind's eval, pdf, sample, split sample and albedo agree (Monte Carlo)" *
          doctest::test_suite("cpu")) {
  SurfaceFrame flat;
  flat.p = float3(0.0f);
  flat.ng = flat.ns = float3(0.0f, 0.0f, 1.0f);
  flat.smooth = 0;
  flat.backface = 0;
  SurfaceFrame tilted = flat;  // ns 35 degrees off ng: folding and absorption below ng
  tilted.ns = dirFromAngles(35.0 * M_PI / 180.0, 0.0);
  tilted.smooth = 1;
  const int n = 200000;
  for (const KindRow& row : kindRows()) {
    for (const KindCase& c : row.cases) {
      const Bsdf b = bsdf_from_material(montecl::deviceMaterial(c.desc), c.albedo);
      const float3 albedo = bsdf_albedo(b);
      for (int fi = 0; fi < 2; ++fi) {
        const SurfaceFrame& sf = fi == 0 ? flat : tilted;
        for (double thetaO : {0.1, 0.9, 1.35}) {
          const float3 wo = dirFromAngles(thetaO, 2.5);
          INFO(row.name << " / " << c.what << (fi ? ", tilted frame" : ", flat frame") << ", theta_o " << thetaO);
          RunningStats sampled[3], uniform[3];
          int pdfMismatch = 0, weightMismatch = 0, fMismatch = 0, splitMismatch = 0, absorbed = 0, deltaMismatch = 0;
          for (int i = 0; i < n; ++i) {
            const float4 u = rng_uniform4(17u, uint(i), uint(fi), 0u);
            const BsdfSample s = bsdf_sample(b, sf, wo, u.x, u.y, u.z);
            const bool delta = (s.flags & MCL_BSDF_DELTA) != 0;
            deltaMismatch += delta != (bsdf_is_delta(b) != 0);
            if (s.pdf > 0.0f && delta) {  // no density: eval and pdf 0, the split weight from wi alone
              const BsdfWeight w = bsdf_direction_weight(b, sf, wo, s.wi, bsdf_pdf(b, sf, wo, s.wi));
              splitMismatch += !w.counts;
              for (int k = 0; k < 3; ++k) splitMismatch += !near(w.weight[k], s.weight[k], 1e-5f);
              pdfMismatch += bsdf_pdf(b, sf, wo, s.wi) != 0.0f;
              weightMismatch += max_abs(bsdf_eval(b, sf, wo, s.wi)) != 0.0f;
            } else if (s.pdf > 0.0f) {
              const float pdf = bsdf_pdf(b, sf, wo, s.wi);
              const float3 fcos = bsdf_eval(b, sf, wo, s.wi), f = bsdf_f(b, sf, wo, s.wi);
              const float cosI = std::fabs(dot(sf.ns, s.wi));
              pdfMismatch += !near(s.pdf, pdf, 1e-3f);
              const BsdfWeight w = bsdf_direction_weight(b, sf, wo, s.wi, pdf);
              splitMismatch += !w.counts;
              for (int k = 0; k < 3; ++k) {
                weightMismatch += !near(s.weight[k], fcos[k] / pdf, 1e-3f);
                fMismatch += !near(f[k] * cosI, fcos[k], 1e-4f);
                splitMismatch += !near(w.weight[k], s.weight[k], 1e-3f);
              }
            } else {
              ++absorbed;
            }
            for (int k = 0; k < 3; ++k) sampled[k].add(s.pdf > 0.0f ? double(s.weight[k]) : 0.0);
            const float4 v = rng_uniform4(17u, uint(i), uint(fi), 1u);
            const float3 wi = uniformSphere(v.x, v.y);
            const float3 fcos = bsdf_eval(b, sf, wo, wi);
            for (int k = 0; k < 3; ++k) uniform[k].add(double(fcos[k]) * 4.0 * M_PI);
          }
          CHECK(pdfMismatch == 0);
          CHECK(weightMismatch == 0);
          CHECK(fMismatch == 0);
          CHECK(splitMismatch == 0);
          CHECK(deltaMismatch == 0);
          // Around the tilted frame the kinds other than diffuse (no folded lobe) may absorb every
          // sample at a grazing wo (below ns, or a mirror direction below ng).
          CHECK((absorbed < n || (fi == 1 && row.tag != MCL_MATERIAL_diffuse)));
          for (int k = 0; k < 3; ++k) {
            const double se = std::hypot(sampled[k].standardError(), uniform[k].standardError());
            INFO("channel " << k << ": sampled " << sampled[k].mean << " +- " << sampled[k].standardError()
                            << ", uniform " << uniform[k].mean << " +- " << uniform[k].standardError() << ", albedo "
                            << albedo[k]);
            // A delta kind's eval is 0 everywhere: only the sampled reflectance is meaningful.
            if (!bsdf_is_delta(b) && c.uniformResolves) CHECK(std::fabs(sampled[k].mean - uniform[k].mean) < 4.0 * se + 1e-6);
            CHECK(sampled[k].mean <= 1.0 + 4.0 * sampled[k].standardError());  // energy
            if (c.albedoIsReflectance && fi == 0) {
              CHECK(std::fabs(sampled[k].mean - albedo[k]) <= 4.0 * sampled[k].standardError() + 1e-6);
              if (c.uniformResolves) CHECK(std::fabs(uniform[k].mean - albedo[k]) <= 4.0 * uniform[k].standardError() + 1e-6);
            }
          }
        }
      }
    }
  }
}

TEST_CASE("diffuse kind: the direct integrator's weight of a folded cosine-lobe direction is Kd times its cosine weight" *
          doctest::test_suite("cpu")) {
  SurfaceFrame sf;
  sf.p = float3(0.0f);
  sf.ng = float3(0.0f, 0.0f, 1.0f);
  sf.ns = dirFromAngles(50.0 * M_PI / 180.0, 0.0);
  sf.smooth = 1;
  sf.backface = 0;
  const float3 wo = dirFromAngles(1.0, M_PI);
  const DiffuseBsdf lambert = diffuse_make(float3(0.5f, 0.4f, 0.3f), float3(0.0f), 1.0f);
  for (int i = 0; i < 2000; ++i) {
    const float4 u = rng_uniform4(3u, uint(i), 0u, 0u);
    // shade_direct's Lambertian direction: the cosine lobe, folded, always traced (its weight is
    // 0 where the folded pdf is).
    const float3 wi = frame_sample_direction(sf, sample_cosine_hemisphere(u.x, u.y));
    int counts = 0;
    const float3 w = diffuse_direction_weight(lambert, sf, wo, wi, diffuse_pdf(lambert, sf, wo, wi), &counts);
    REQUIRE(counts);
    REQUIRE(w == lambert.kd * cosine_weight(sf.ns, sf.ng, sf.smooth, wi));
  }
}

}  // namespace test_file_material_kinds
