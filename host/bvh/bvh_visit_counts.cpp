// bvh_visit_counts.cpp: see bvh_visit_counts.h. The loop is wide_closest_hit's / wide_any_hit's, with the
// same visit order and culling, plus two counters; keep them in step with traverse_wide.h.
#include "bvh/bvh_visit_counts.h"

#include <vector>

#include "kernels/shared/traverse.h"
#include "util/parallel_for.h"

namespace montecl {
namespace {

void countRay(const WideNode* nodes, const Triangle* tris, const AlphaScene* alpha, float3 org,
              float3 dir, float tmax, bool anyHit, double& nodeCount, double& leafCount) {
  float hitT = tmax;
  RayBoxCtx ctx = make_ray_box_ctx(org, dir);
  uint stack[MCL_WIDE_STACK_SIZE];
  float stackT[MCL_WIDE_STACK_SIZE];
  uint sp = 0;
  uint ref = ray_is_finite(org, dir) ? 0u : MCL_WIDE_EMPTY;
  for (;;) {
    if (ref == MCL_WIDE_EMPTY) {
    } else if (ref & MCL_WIDE_LEAF) {
      leafCount += 1.0;
      uint first = wide_leaf_first(ref), last = first + wide_leaf_count(ref) - 1u;
      for (uint b = first; b <= last; b += 4u) {
        float4 u, v;
        float4 t = ray_triangle4(tris, b, last, org, dir, anyHit ? tmax : hitT, &u, &v);
        if (alpha) t = alpha_filter4(alpha, tris, b, last, t, u, v, anyHit ? tmax : hitT, org, dir);
        float bt = fminf(fminf(t.x, t.y), fminf(t.z, t.w));
        if (anyHit && bt < tmax) return;
        if (bt < hitT) hitT = bt;
      }
    } else {
      nodeCount += 1.0;
      uint next = wide_visit(nodes, tris, ref, &ctx, anyHit ? tmax : hitT, stack, stackT, &sp);
      if (next != MCL_WIDE_EMPTY) {
        ref = next;
        continue;
      }
    }
    if (anyHit) {
      if (sp == 0) return;
      ref = stack[--sp];
    } else if (!pop_entered(stack, stackT, &sp, hitT, &ref)) {
      return;
    }
  }
}

}  // namespace

VisitCounts countWideVisits(const Bvh& bvh, const std::vector<Ray>& rays, bool anyHit,
                            const AlphaScene* alpha, unsigned threadCount) {
  VisitCounts c;
  if (rays.empty() || bvh.nodes.empty()) return c;
  const WideNode* nodes = bvh.wideNodes().data();
  const unsigned threads = threadCount == 0 ? 1u : threadCount;
  std::vector<double> n(threads, 0.0), l(threads, 0.0);
  parallelChunks(rays.size(), threads, 4096, [&](std::size_t slot, std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      countRay(nodes, bvh.triangles.data(), alpha, xyz(rays[i].origin), xyz(rays[i].dir), rays[i].dir.w,
               anyHit, n[slot], l[slot]);
  });
  for (unsigned s = 0; s < threads; ++s) {  // integer-valued sums: exact in any order
    c.nodes += n[s];
    c.leaves += l[s];
  }
  c.nodes /= double(rays.size());
  c.leaves /= double(rays.size());
  return c;
}

}  // namespace montecl
