// parallel_for.h: the one parallel loop of the host code (BVH build, host backend, bench ray sets
// and Embree tracing). [0, n) is cut into contiguous chunks run on up to `threads` std::threads
// (0 = std::thread::hardware_concurrency()), the calling thread among them. Work too small to pay
// for a thread start runs inline: the number of threads is min(threads, n / minItemsPerThread),
// and at most one thread means body runs on the caller with no thread started.
// Scheduling: grain 0 (the default) gives thread k the k-th of t equal chunks, so chunk k is a
// stable per-thread slot for partial results; grain > 0 hands out chunks of `grain` items in
// order through an atomic counter, for work of uneven cost (tracing rays). An exception thrown by
// body stops handing out chunks; after every thread has joined, the one of the lowest thread index
// is rethrown.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace montecl {

// Threads parallelChunks and parallelFor run n items on (>= 1).
inline unsigned parallelThreadCount(std::size_t n, unsigned threads, std::size_t minItemsPerThread) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t byWork = n / std::max<std::size_t>(1, minItemsPerThread);
  return static_cast<unsigned>(std::max<std::size_t>(1, std::min<std::size_t>(threads, byWork)));
}

// Runs body(chunk, begin, end) over contiguous chunks [begin, end) covering [0, n) (n > 0). With
// grain 0, chunk is in [0, parallelThreadCount(n, threads, minItemsPerThread)) and is the index of
// the thread running it; with grain > 0, chunk = begin / grain.
template <class Body>
void parallelChunks(std::size_t n, unsigned threads, std::size_t minItemsPerThread, const Body& body,
                    std::size_t grain = 0) {
  if (n == 0) return;
  const unsigned t = parallelThreadCount(n, threads, minItemsPerThread);
  if (t <= 1) {
    if (grain == 0) {
      body(std::size_t(0), std::size_t(0), n);
    } else {
      for (std::size_t b = 0; b < n; b += grain) body(b / grain, b, std::min(n, b + grain));
    }
    return;
  }
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> errors(t);
  auto worker = [&](unsigned k) {
    try {
      if (grain == 0) {
        body(std::size_t(k), n * k / t, n * (k + 1) / t);
        return;
      }
      for (;;) {
        std::size_t b = next.fetch_add(grain);
        if (b >= n) return;
        body(b / grain, b, std::min(n, b + grain));
      }
    } catch (...) {
      errors[k] = std::current_exception();
      next.store(n);  // no more chunks for anyone
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(t - 1);
  for (unsigned k = 1; k < t; ++k) pool.emplace_back(worker, k);
  worker(0);
  for (std::thread& th : pool) th.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

// Runs body(i) for every i in [0, n), in the contiguous per-thread chunks of parallelChunks
// (grain 0).
template <class Body>
void parallelFor(std::size_t n, unsigned threads, std::size_t minItemsPerThread, const Body& body) {
  parallelChunks(n, threads, minItemsPerThread, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) body(i);
  });
}

}  // namespace montecl
