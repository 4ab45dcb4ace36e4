// emitters.cpp: builds the emitter CDF on the host (in double, stored as float; the last entry
// is exactly 1 so every u in [0, 1) picks an emitter), over the input triangles in input order;
// for textured emitters it reads the emission textures and writes each triangle's mean emission
// luminance into its attributes (TriangleShading::tv.w), which the kernels' pdfs read back.
#include "render/emitters.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

#include "kernels/shared/lights.h"
#include "render/emitter_guide.h"
#include "kernels/shared/surface_texture.h"

namespace montecl {
namespace {

// Whether the open box (x0, x1) x (y0, y1) and the triangle with corners (px[k], py[k]) overlap
// (separating axes: the box's two and the triangle's three edge normals).
bool boxMeetsTriangle(double x0, double x1, double y0, double y1, const double px[3], const double py[3]) {
  if (std::max({px[0], px[1], px[2]}) <= x0 || std::min({px[0], px[1], px[2]}) >= x1) return false;
  if (std::max({py[0], py[1], py[2]}) <= y0 || std::min({py[0], py[1], py[2]}) >= y1) return false;
  for (int e = 0; e < 3; ++e) {
    const int a = e, b = (e + 1) % 3, c = (e + 2) % 3;
    const double nx = py[b] - py[a], ny = px[a] - px[b];  // an edge normal
    const double d = nx * px[a] + ny * py[a], side = nx * px[c] + ny * py[c] - d;
    double lo = INFINITY, hi = -INFINITY;
    for (double x : {x0, x1})
      for (double y : {y0, y1}) lo = std::min(lo, nx * x + ny * y - d), hi = std::max(hi, nx * x + ny * y - d);
    if ((side >= 0.0 && hi <= 0.0) || (side <= 0.0 && lo >= 0.0)) return false;  // the box beyond the edge
  }
  return true;
}

// Whether Le = Ke x the texture (bilinear, finest level kept) can be non-zero anywhere on triangle
// tri: some texel with Ke x texel > 0 in a channel has a bilinear footprint (one texel around its
// centre) that meets the triangle's UV image (any repeat of it). Writes the largest luminance of
// those texels to maxLum.
// Whole-texture answers of mayEmit, by (texture, Ke): where a triangle needs every texel (a
// transform, a wrap mode other than repeat, many repeats) the answer does not depend on the
// triangle, so one read of the texture serves every triangle of the material; reading it per
// triangle made the table quadratic (thousands of triangles x millions of texels).
struct WholeTextureKey {
  std::uint32_t texture;
  std::array<std::uint32_t, 3> ke;
  bool operator<(const WholeTextureKey& o) const { return std::tie(texture, ke) < std::tie(o.texture, o.ke); }
};
struct WholeTextureAnswer {
  bool any;
  float maxLum;
};
using WholeTextureCache = std::map<WholeTextureKey, WholeTextureAnswer>;

bool mayEmit(TextureTables tt, const Material& m, const Triangle& tri, const TriangleShading& sh, float& maxLum,
             WholeTextureCache& cache) {
  const TextureDesc d = tt.textures[as_uint(m.maps.x)];
  const TextureLevel l = tt.levels[d.firstLevel];
  const bool uv = (as_uint(tri.e2.w) & MCL_ATTR_UV) != 0;
  // The triangle in texel units (texel x's centre at x + 0.5), shifted by whole repeats to near 0.
  double px[3] = {uv ? sh.n0.w : 0.0, uv ? sh.n1.w : 0.0, uv ? sh.n2.w : 0.0};
  double py[3] = {uv ? sh.tv.x : 0.0, uv ? sh.tv.y : 0.0, uv ? sh.tv.z : 0.0};
  const double su = std::floor(std::min({px[0], px[1], px[2]})), sv = std::floor(std::min({py[0], py[1], py[2]}));
  for (int k = 0; k < 3; ++k) px[k] = (px[k] - su) * l.width, py[k] = (py[k] - sv) * l.height;
  const double xa = std::floor(std::min({px[0], px[1], px[2]}) - 1.0), xb = std::ceil(std::max({px[0], px[1], px[2]}));
  const double ya = std::floor(std::min({py[0], py[1], py[2]}) - 1.0), yb = std::ceil(std::max({py[0], py[1], py[2]}));
  // Too many texels to test one by one (a triangle spanning many repeats): every texel counts.
  // So does a texture read through its own transform or a wrap mode other than repeat (the
  // triangle's image above is in the surface's UVs, not the texture's).
  const bool plain = d.uvRow0 == float4(1.0f, 0.0f, 0.0f, 0.0f) && d.uvRow1 == float4(0.0f, 1.0f, 0.0f, 0.0f);
  const bool all = !plain || (xb - xa + 1.0) * (yb - ya + 1.0) > 4.0 * double(l.width) * double(l.height);
  const float3 ke = xyz(m.emission);
  const WholeTextureKey key{as_uint(m.maps.x), {as_uint(ke.x), as_uint(ke.y), as_uint(ke.z)}};
  if (all)
    if (const auto it = cache.find(key); it != cache.end()) {
      maxLum = it->second.maxLum;
      return it->second.any;
    }
  bool any = false;
  maxLum = 0.0f;
  for (double y = all ? 0.0 : ya; y <= (all ? double(l.height) - 1.0 : yb); y += 1.0)
    for (double x = all ? 0.0 : xa; x <= (all ? double(l.width) - 1.0 : xb); x += 1.0) {
      const float3 e = ke * xyz(texel_at(tt, l, texture_wrap(int(x), l.width), texture_wrap(int(y), l.height)));
      if (!(e.x > 0.0f || e.y > 0.0f || e.z > 0.0f)) continue;
      if (!all && !boxMeetsTriangle(x - 0.5, x + 1.5, y - 0.5, y + 1.5, px, py)) continue;
      any = true;
      maxLum = std::max(maxLum, luminance(e));
    }
  if (all) cache[key] = WholeTextureAnswer{any, maxLum};
  return any;
}

// Mean luminance of a textured emitter's Le over triangle slot i: material_emission at an n x n
// grid folded onto the triangle (uniform in area), n from the triangle's size in texels (1 to 16).
// Exactly 0 only when Le is 0 everywhere on it (mayEmit); a triangle that emits somewhere between
// the grid's points gets a small positive weight (any positive weight keeps light sampling unbiased).
float texturedEmitterLuminance(TextureTables tt, const Material& m, const Triangle& tri, const TriangleShading& sh,
                               WholeTextureCache& cache) {
  if (!(as_uint(tri.e2.w) & MCL_ATTR_UV)) return emitter_luminance(tt, &m, &tri, &sh);  // one colour
  const TextureDesc d = tt.textures[as_uint(m.maps.x)];
  const TextureLevel l = tt.levels[d.firstLevel];
  const float scale = texture_uv_scale(d);
  const double texels = double(uv_area(&tri, &sh)) * double(scale) * double(scale) * double(l.width) * double(l.height);
  const int n = int(std::clamp(std::ceil(std::sqrt(texels)), 1.0, 16.0));
  double sum = 0.0;
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) {
      float a = (float(j) + 0.5f) / float(n), b = (float(k) + 0.5f) / float(n);
      if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
      sum += double(luminance(material_emission(tt, &m, &tri, &sh, a, b)));
    }
  const float mean = float(sum / double(n * n));
  if (mean > 0.0f) return mean;
  float maxLum = 0.0f;
  if (!mayEmit(tt, m, tri, sh, maxLum, cache)) return 0.0f;
  return std::max(maxLum * (1.0f / 1024.0f), 1e-30f);
}

}  // namespace

double emitterWeight(float area, const glm::vec3& emission) {
  return double(area) * double(luminance(emission));
}

EmitterTable buildEmitterTable(const Bvh& bvh, const std::vector<MaterialDesc>& materials,
                               const EmissionTextures* textured) {
  EmitterTable table;
  std::vector<double> power;
  double total = 0.0;
  // Input order, each triangle through its canonical slot (a spatial split's copies are skipped):
  // the table, and so the light samples, do not depend on the tree.
  const std::size_t m = bvh.triangles.size();
  std::vector<std::uint32_t> slots;
  if (bvh.order.size() == m) {
    slots.assign(m, MCL_NO_HIT);
    for (std::size_t i = 0; i < m; ++i)
      if (as_uint(bvh.triangles[i].e1.w) == i && bvh.order[i] < m) slots[bvh.order[i]] = std::uint32_t(i);
  } else {  // a Bvh assembled by hand (no order): its slots as they are
    for (std::size_t i = 0; i < m; ++i) slots.push_back(std::uint32_t(i));
  }
  const TriangleShading none{};
  WholeTextureCache wholeTexture;
  for (std::uint32_t i : slots) {
    if (i == MCL_NO_HIT) continue;
    const Triangle& t = bvh.triangles[i];
    const std::uint32_t mi = triangle_material(&t);
    const glm::vec3 le = materials[mi].emission;
    float area = triangle_area(&t);
    double p = emitterWeight(area, le);
    if (textured && as_uint((*textured->materials)[mi].maps.x) != MCL_NO_TEXTURE && p > 0.0) {
      std::vector<TriangleShading>& sh = *textured->shading;
      const bool uv = (as_uint(t.e2.w) & MCL_ATTR_UV) != 0 && i < sh.size();
      const float lum = texturedEmitterLuminance(textured->tables, (*textured->materials)[mi], t, uv ? sh[i] : none,
                                                wholeTexture);
      if (uv) sh[i].tv.w = lum;
      p = double(area) * double(lum);
    }
    if (!(p > 0.0)) continue;
    Emitter e{};
    e.tri = uint(i);
    e.area = area;
    table.emitters.push_back(e);
    power.push_back(p);
    total += p;
  }
  double running = 0.0;
  for (std::size_t k = 0; k < table.emitters.size(); ++k) {
    running += power[k];
    table.emitters[k].cdf = float(running / total);
  }
  if (!table.emitters.empty()) table.emitters.back().cdf = 1.0f;
  fillEmitterGuide(table.emitters);
  table.totalPower = float(total);
  return table;
}

bool hasEmitter(const Scene& scene) {
  for (const SceneTriangle& t : scene.triangles) {
    // The edges as Bvh::triangles holds them; their cross product in double, since its squared
    // length in float underflows at a scale of 2^-40 (the kernels' triangle_area rescales).
    const glm::dvec3 e1(t.v[1] - t.v[0]), e2(t.v[2] - t.v[0]);
    if (emitterWeight(float(0.5 * glm::length(glm::cross(e1, e2))), scene.materials[t.material].emission) > 0.0)
      return true;
  }
  return false;
}

}  // namespace montecl
