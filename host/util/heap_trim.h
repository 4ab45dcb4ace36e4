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

// Fixes glibc's mmap threshold at its default (128 KiB): every larger block is its own mapping,
// returned to the system when freed. Left dynamic, the threshold rises to the largest block freed
// so far (up to 32 MiB) and the trim threshold to twice that, so after the loaders' temporaries
// are freed, arrays of up to 32 MiB come from the heaps, and a thread's heap keeps up to 64 MiB
// of freed memory resident (malloc_trim does not shrink a thread heap's top). Call once, first.
inline void fixMmapThreshold() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
#endif
}

}  // namespace montecl
