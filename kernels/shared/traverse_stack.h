// traverse_stack.h: what every closest-hit traversal shares (binary and wide layouts, single rays
// and packets): the order of two hits, the leaf tests' tmax, and the stack pop (entries carry the
// distance at which the ray enters them, and those beyond the closest hit so far are skipped).
// Reads and shrinks a private stack; pure.
#pragma once
#include "compat.h"

// Pops entries until one the ray enters at or before tHit: stores its node in *ref and returns 1;
// returns 0 when the stack is empty.
MCL_INLINE int pop_entered(const uint* stack, const float* stackT, uint* sp, float tHit, uint* ref) {
  while (*sp > 0u) {
    --*sp;
    if (stackT[*sp] <= tHit) {
      *ref = stack[*sp];
      return 1;
    }
  }
  return 0;
}

// Whether a triangle hit at t (canonical slot canon) comes before the hit so far (bestT, bestCanon):
// it is nearer, or at exactly the same t it has the lower canonical slot. The hit a traversal keeps
// is then the first in this order whatever order it meets the triangles in, so the packet and the
// single-ray traversals keep the same one without redoing rays that meet two triangles at one t
// (coincident faces, a shared edge). t INFINITY is no hit.
MCL_INLINE int hit_before(float t, uint canon, float bestT, uint bestCanon) {
  return t < bestT || (t == bestT && canon < bestCanon && t != INFINITY);
}

// The tmax a leaf's triangle tests take for a ray whose hit so far is at t (tri MCL_NO_HIT: none,
// t is the ray's tmax): one float beyond a hit's t, so that a triangle at exactly that t is seen.
MCL_INLINE float leaf_tmax(float t, uint tri) { return tri == MCL_NO_HIT ? t : as_float(as_uint(t) + 1u); }
