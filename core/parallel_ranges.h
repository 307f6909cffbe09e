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

// Calls body(begin, end) in parallel on disjoint ranges that together cover [0, n), on as many
// threads as the caller's oneTBB arena allows. oneTBB is an uninstrumented library:
// ThreadSanitizer cannot see its task scheduler's synchronisation and reports its internals (and
// the stack frames it reuses) as races. Its builds hand out the indices one at a time to plain
// std::threads instead (`threads` of them, or one per core when 0), which it sees whole; each
// index's work is the same.
template <typename Body>
void parallel_ranges(int n, [[maybe_unused]] int threads, const Body& body) {
#ifdef PRISM_TSAN
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int i; (i = next.fetch_add(1)) < n;) body(i, i + 1);
  };
  const int count = threads > 0 ? threads : int(std::max(2u, std::thread::hardware_concurrency()));
  std::vector<std::thread> workers;
  for (int i = 1; i < count; ++i) workers.emplace_back(worker);
  worker();
  for (auto& t : workers) t.join();
#else
  tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
#endif
}

}  // namespace prism
