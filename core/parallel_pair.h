// parallel_pair: two calls run side by side, on oneTBB, or on a plain std::thread ThreadSanitizer can see.
#pragma once

#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <thread>

#include "core/tsan_annotations.h"

namespace prism {

// Calls first() and second(), in parallel where the caller's oneTBB arena has more than one
// thread, and returns when both have. ThreadSanitizer cannot see oneTBB's synchronisation (an
// uninstrumented library; see parallel_ranges.h), so its builds run second() on a std::thread.
template <typename First, typename Second>
void parallel_pair(const First& first, const Second& second) {
#ifdef PRISM_TSAN
  if (tbb::this_task_arena::max_concurrency() < 2) {
    first();
    second();
    return;
  }
  std::thread other(second);
  first();
  other.join();
#else
  tbb::parallel_invoke(first, second);
#endif
}

}  // namespace prism
