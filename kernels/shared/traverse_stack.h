// traverse_stack.h: the closest-hit traversals' stack pop (binary and wide layouts): entries
// carry the distance at which the ray enters them, and those beyond the closest hit so far are
// skipped. Reads and shrinks a private stack; pure.
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
