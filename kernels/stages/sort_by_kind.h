// sort_by_kind.h: reads a fused path group's bounce queue entries (their hits, the triangles and
// materials hit) and reorders the entries in place (rays, hits, path ids and, with instances, hit
// instances) so that hits of one material kind lie together, misses first, each kind in queue
// order (a stable counting sort). A bounce's packets then mostly hold one kind, so shade_path runs
// one kind's branch per packet instead of every kind's under masks (pbrt-v4 keeps a queue per
// material, Cycles sorts by shader). Nothing depends on the entries' order: each path's random
// numbers, state and shadow slots are found by its id (shade_path.h), so the image keeps its bits.
// Camera rays (bounce 0, whose ids are their positions) and W = 1 are left as they are.
#pragma once
#include "stage_common.h"

#define MCL_SORT_KEYS (MCL_MATERIAL_KIND_COUNT + 1)
// The most entries a group holds (wave_fused.h: W packets of MCL_FUSED_PATH_PACKETS).
#define MCL_SORT_MAX (MCL_LANES * MCL_FUSED_PATH_PACKETS)

MCL_INLINE void fused_sort_by_kind(MCL_GLOBAL Ray* rays, MCL_GLOBAL Hit* hits, MCL_GLOBAL uint* pathIds,
                                   MCL_GLOBAL uint* hitInstances, int placed, MCL_GLOBAL const Triangle* tris,
                                   MCL_GLOBAL const Material* materials, uint first, uint n) {
  unsigned char key[MCL_SORT_MAX];
  uint count[MCL_SORT_KEYS];
  for (uint k = 0; k < MCL_SORT_KEYS; ++k) count[k] = 0u;
  for (uint i = 0; i < n; ++i) {
    uint tri = hits[first + i].tri;
    uint k = tri == MCL_NO_HIT ? 0u : 1u + as_uint(materials[triangle_material(&tris[tri])].alpha.w);
    k = k < MCL_SORT_KEYS ? k : 0u;
    key[i] = (unsigned char)k;
    ++count[k];
  }
  uint kinds = 0u;
  for (uint k = 0; k < MCL_SORT_KEYS; ++k) kinds += count[k] > 0u;
  if (kinds < 2u) return;  // one kind already
  uint start[MCL_SORT_KEYS];
  uint at = 0u;
  for (uint k = 0; k < MCL_SORT_KEYS; ++k) {
    start[k] = at;
    at += count[k];
  }
  unsigned char dest[MCL_SORT_MAX];  // each entry's place (n <= 256)
  unsigned char done[MCL_SORT_MAX];
  for (uint i = 0; i < n; ++i) {
    dest[i] = (unsigned char)(start[key[i]]++);
    done[i] = 0;
  }
  // Each cycle of the permutation: carry the entry at its start to its place, the one there to
  // its own place, and so on until the cycle closes.
  for (uint i = 0; i < n; ++i) {
    if (done[i] || dest[i] == i) continue;
    Ray r = rays[first + i];
    Hit h = hits[first + i];
    uint id = pathIds[first + i], inst = placed ? hitInstances[first + i] : 0u;
    uint j = i;
    do {
      uint k = dest[j];
      Ray r2 = rays[first + k];
      Hit h2 = hits[first + k];
      uint id2 = pathIds[first + k];
      rays[first + k] = r;
      hits[first + k] = h;
      pathIds[first + k] = id;
      if (placed) {
        uint inst2 = hitInstances[first + k];
        hitInstances[first + k] = inst;
        inst = inst2;
      }
      r = r2;
      h = h2;
      id = id2;
      done[k] = 1;
      j = k;
    } while (j != i);
  }
}
