// heap_trim.h: trimHeap() hands the heap's free pages back to the system. glibc keeps freed blocks
// below its mmap threshold (which rises after large frees) in the heap, resident; after freeing
// large arrays (a render's host copies, released device buffers on a CPU OpenCL device) a trim
// makes the resident set shrink at once. A no-op on other C libraries.
#pragma once
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace montecl {

inline void trimHeap() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace montecl
