// Shared set-up of the fuzz targets: a memory limit far under libFuzzer's RSS limit (2 GiB).
#pragma once

#include "core/memory_limit.h"

namespace prism::fuzz {

// Called once from each target's first input: inputs that declare more than this are refused by
// prism's own estimates (tested), instead of being reported by libFuzzer as out-of-memory.
inline void set_fuzz_limits() {
  static const bool once = [] {
    set_memory_limit(uint64_t(32) << 20);
    return true;
  }();
  (void)once;
}

}  // namespace prism::fuzz
