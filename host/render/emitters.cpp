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
#include <utility>
#include <vector>

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

// The emitting texels of one texture under one Ke (the finest level kept): level 0 holds, per
// texel, max(0, luminance(Ke x texel)) where some channel of Ke x texel is > 0 and -1 where none
// is; each coarser level the largest of the (up to) 2 x 2 entries below it, up to one entry. Built
// once per (texture, Ke) in time linear in the texels; mayEmit then asks it about a triangle's
// footprint without reading every texel of it (reading the whole texture per triangle made the
// table quadratic: thousands of triangles x millions of texels took minutes).
struct EmissionPyramid {
  std::vector<std::vector<float>> level;
  std::vector<std::uint32_t> width, height;
};

EmissionPyramid buildEmissionPyramid(TextureTables tt, const TextureLevel& l, float3 ke) {
  EmissionPyramid p;
  std::vector<float> base(std::size_t(l.width) * l.height);
  for (std::uint32_t y = 0; y < l.height; ++y)
    for (std::uint32_t x = 0; x < l.width; ++x) {
      const float3 e = ke * xyz(texel_at(tt, l, x, y));
      // std::max keeps 0 for a NaN luminance, as the running maximum of the texel loop did.
      base[std::size_t(y) * l.width + x] = (e.x > 0.0f || e.y > 0.0f || e.z > 0.0f) ? std::max(0.0f, luminance(e)) : -1.0f;
    }
  p.level.push_back(std::move(base));
  p.width.push_back(l.width);
  p.height.push_back(l.height);
  while (p.width.back() > 1 || p.height.back() > 1) {
    const std::uint32_t w = p.width.back(), h = p.height.back(), w2 = (w + 1) / 2, h2 = (h + 1) / 2;
    const std::vector<float>& below = p.level.back();
    std::vector<float> up(std::size_t(w2) * h2);
    for (std::uint32_t y = 0; y < h2; ++y)
      for (std::uint32_t x = 0; x < w2; ++x) {
        float v = -1.0f;
        for (std::uint32_t dy = 0; dy < 2; ++dy)
          for (std::uint32_t dx = 0; dx < 2; ++dx)
            if (2 * x + dx < w && 2 * y + dy < h) v = std::max(v, below[std::size_t(2 * y + dy) * w + 2 * x + dx]);
        up[std::size_t(y) * w2 + x] = v;
      }
    p.level.push_back(std::move(up));
    p.width.push_back(w2);
    p.height.push_back(h2);
  }
  return p;
}

// Pyramids by (texture, Ke), built on first use. At most kPyramidBytes are kept: past that the
// cache starts over (many materials sharing one large emissive map under different Ke).
struct PyramidKey {
  std::uint32_t texture;
  std::array<std::uint32_t, 3> ke;
  bool operator<(const PyramidKey& o) const { return std::tie(texture, ke) < std::tie(o.texture, o.ke); }
};
struct EmissionPyramids {
  static constexpr std::size_t kPyramidBytes = std::size_t(512) << 20;
  std::map<PyramidKey, EmissionPyramid> byKey;
  std::size_t bytes = 0;
  const EmissionPyramid& get(TextureTables tt, std::uint32_t texture, const TextureLevel& l, float3 ke) {
    const PyramidKey key{texture, {as_uint(ke.x), as_uint(ke.y), as_uint(ke.z)}};
    if (const auto it = byKey.find(key); it != byKey.end()) return it->second;
    const std::size_t need = std::size_t(l.width) * l.height * sizeof(float) * 4 / 3;
    if (bytes + need > kPyramidBytes) byKey.clear(), bytes = 0;
    bytes += need;
    return byKey.emplace(key, buildEmissionPyramid(tt, l, ke)).first->second;
  }
};

// What mayEmit looks for: some emitting texel, in texels [x0, x1] x [y0, y1] of level 0 (shifted
// by (ox, oy) whole repeats into the triangle's texel coordinates), whose bilinear footprint (one
// texel around its centre) meets the triangle (px, py); the largest of their entries. Branch and
// bound over the pyramid: a block with no emitting texel, one whose footprints all miss the
// triangle, or one that cannot raise the largest entry found, is not opened. The answer is the
// texel-by-texel loop's.
struct FootprintSearch {
  const EmissionPyramid& p;
  const double *px, *py;
  long long x0, x1, y0, y1, ox, oy;
  bool any = false;
  float maxLum = 0.0f;

  void visit(std::size_t k, long long bx, long long by) {
    const float v = p.level[k][std::size_t(by) * p.width[k] + std::size_t(bx)];
    if (v < 0.0f || (any && v <= maxLum)) return;
    const long long xa = std::max(x0, bx << k), xb = std::min(x1, ((bx + 1) << k) - 1);
    const long long ya = std::max(y0, by << k), yb = std::min(y1, ((by + 1) << k) - 1);
    if (xa > xb || ya > yb) return;
    if (!boxMeetsTriangle(double(xa + ox) - 0.5, double(xb + ox) + 1.5, double(ya + oy) - 0.5, double(yb + oy) + 1.5, px,
                          py))
      return;
    if (k == 0) {
      any = true;
      maxLum = std::max(maxLum, v);
      return;
    }
    // The larger child first: the bound then cuts more.
    std::array<std::pair<float, int>, 4> order;
    int n = 0;
    for (int c = 0; c < 4; ++c) {
      const long long cx = 2 * bx + (c & 1), cy = 2 * by + (c >> 1);
      if (cx >= p.width[k - 1] || cy >= p.height[k - 1]) continue;
      order[std::size_t(n++)] = {p.level[k - 1][std::size_t(cy) * p.width[k - 1] + std::size_t(cx)], c};
    }
    std::sort(order.begin(), order.begin() + n, [](const auto& a, const auto& b) { return a.first > b.first; });
    for (int i = 0; i < n; ++i) visit(k - 1, 2 * bx + (order[std::size_t(i)].second & 1), 2 * by + (order[std::size_t(i)].second >> 1));
  }
};

// Whether Le = Ke x the texture (bilinear, finest level kept) can be non-zero anywhere on triangle
// tri: some texel with Ke x texel > 0 in a channel has a bilinear footprint (one texel around its
// centre) that meets the triangle's UV image (any repeat of it). Writes the largest luminance of
// those texels to maxLum.
bool mayEmit(TextureTables tt, const Material& m, const Triangle& tri, const TriangleShading& sh, float& maxLum,
             EmissionPyramids& pyramids) {
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
  const EmissionPyramid& p = pyramids.get(tt, as_uint(m.maps.x), l, xyz(m.emission));
  if (all) {
    const float top = p.level.back()[0];
    maxLum = std::max(0.0f, top);
    return top >= 0.0f;
  }
  // The texels [xa, xb] x [ya, yb] wrap (repeat) into the texture: one search per repeat they span.
  const long long w = l.width, h = l.height;
  const auto floorDiv = [](long long a, long long b) { return a >= 0 ? a / b : -((-a + b - 1) / b); };
  FootprintSearch s{p, px, py, 0, 0, 0, 0, 0, 0};
  for (long long ty = floorDiv((long long)ya, h); ty <= floorDiv((long long)yb, h); ++ty)
    for (long long tx = floorDiv((long long)xa, w); tx <= floorDiv((long long)xb, w); ++tx) {
      s.ox = tx * w, s.oy = ty * h;
      s.x0 = std::max((long long)xa, s.ox) - s.ox, s.x1 = std::min((long long)xb, s.ox + w - 1) - s.ox;
      s.y0 = std::max((long long)ya, s.oy) - s.oy, s.y1 = std::min((long long)yb, s.oy + h - 1) - s.oy;
      s.visit(p.level.size() - 1, 0, 0);
    }
  maxLum = s.maxLum;
  return s.any;
}

// Mean luminance of a textured emitter's Le over triangle slot i: material_emission at an n x n
// grid folded onto the triangle (uniform in area), n from the triangle's size in texels (1 to 16).
// Exactly 0 only when Le is 0 everywhere on it (mayEmit); a triangle that emits somewhere between
// the grid's points gets a small positive weight (any positive weight keeps light sampling unbiased).
float texturedEmitterLuminance(TextureTables tt, const Material& m, const Triangle& tri, const TriangleShading& sh,
                               EmissionPyramids& pyramids) {
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
  if (!mayEmit(tt, m, tri, sh, maxLum, pyramids)) return 0.0f;
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
  EmissionPyramids pyramids;
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
                                                pyramids);
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
