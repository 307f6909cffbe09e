// A parallel loop over index ranges: oneTBB's, or plain std::threads ThreadSanitizer can see.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "core/tsan_annotations.h"

namespace prism {

// Calls body(begin, end) in parallel on disjoint ranges that together cover [0, n), none split
// below `grain` indices, on as many threads as the caller's oneTBB arena allows. oneTBB is an
// uninstrumented library: ThreadSanitizer cannot see its task scheduler's synchronisation and
// reports its internals (and the stack frames it reuses) as races. Its builds hand ranges of
// `grain` indices to plain std::threads instead (`threads` of them, or one per core when 0),
// which it sees whole; the ranges cover the same indices and each index's work is the same.
template <typename Body>
void parallel_ranges(int n, int grain, [[maybe_unused]] int threads, const Body& body) {
  grain = std::max(grain, 1);
#ifdef PRISM_TSAN
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int first; (first = next.fetch_add(grain)) < n;) body(first, std::min(first + grain, n));
  };
  const int count = threads > 0 ? threads : int(std::max(2u, std::thread::hardware_concurrency()));
  std::vector<std::thread> workers;
  for (int i = 1; i < count; ++i) workers.emplace_back(worker);
  worker();
  for (auto& t : workers) t.join();
#else
  tbb::parallel_for(tbb::blocked_range<int>(0, n, size_t(grain)),
                    [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
#endif
}

}  // namespace prism
