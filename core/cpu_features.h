// cpu_has_avx2: whether this CPU runs the AVX2 kernels (functions built with target("avx2")).
#pragma once

namespace prism {

// Asked once; the kernels' callers check it and fall back to their SSE forms without it.
inline bool cpu_has_avx2() {
  static const bool avx2 = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return avx2;
}

}  // namespace prism
