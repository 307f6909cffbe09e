// Float8: eight floats in one vector, with the operations Float4 has, so importance_at runs on eight lanes.
#pragma once

#include <cstdint>

#include "core/float4.h"

namespace prism {

// A GCC/Clang vector of eight lanes. Code compiled for AVX (a target("avx2") function with the
// formula inlined into it) runs each operation as one AVX instruction; elsewhere it compiles to
// pairs of SSE ones. Every operation rounds, compares and picks as Float4's does (float4.h), so lane
// k gives the bits the float form gives for lane k's inputs. The operations are always inlined: no
// call passes an eight-lane vector, whose calling convention differs with and without AVX.
typedef float Float8Lanes __attribute__((vector_size(32)));
typedef int32_t Mask8Lanes __attribute__((vector_size(32)));

struct Float8 {
  Float8Lanes v;
  [[gnu::always_inline]] Float8() : v(Float8Lanes{}) {}
  [[gnu::always_inline]] explicit Float8(float x) : v(Float8Lanes{} + x) {}
  [[gnu::always_inline]] explicit Float8(Float8Lanes x) : v(x) {}
#if defined(__SSE2__)
  // Four lanes from each: lo in lanes 0-3, hi in 4-7.
  [[gnu::always_inline]] Float8(Float4 lo, Float4 hi) : v(__builtin_shufflevector(lo.v, hi.v, 0, 1, 2, 3, 4, 5, 6, 7)) {}
#endif
};

// A lane mask: all bits set where a comparison held.
struct Mask8 {
  Mask8Lanes v;
};

[[gnu::always_inline]] inline Float8 operator+(Float8 a, Float8 b) { return Float8(a.v + b.v); }
[[gnu::always_inline]] inline Float8 operator-(Float8 a, Float8 b) { return Float8(a.v - b.v); }
[[gnu::always_inline]] inline Float8 operator*(Float8 a, Float8 b) { return Float8(a.v * b.v); }
[[gnu::always_inline]] inline Float8 operator/(Float8 a, Float8 b) { return Float8(a.v / b.v); }
[[gnu::always_inline]] inline Mask8 operator<(Float8 a, Float8 b) { return {a.v < b.v}; }
[[gnu::always_inline]] inline Mask8 operator>(Float8 a, Float8 b) { return {a.v > b.v}; }
[[gnu::always_inline]] inline Mask8 operator>=(Float8 a, Float8 b) { return {a.v >= b.v}; }
[[gnu::always_inline]] inline Mask8 both(Mask8 a, Mask8 b) { return {a.v & b.v}; }
[[gnu::always_inline]] inline Float8 select(Mask8 m, Float8 a, Float8 b) {
  const Mask8Lanes bits = (m.v & reinterpret_cast<Mask8Lanes>(a.v)) | (~m.v & reinterpret_cast<Mask8Lanes>(b.v));
  return Float8(reinterpret_cast<Float8Lanes>(bits));
}
// a < b ? a : b and a > b ? a : b lane by lane, as minps and maxps (and the scalar vmin, vmax) pick.
[[gnu::always_inline]] inline Float8 vmin(Float8 a, Float8 b) { return select(a < b, a, b); }
[[gnu::always_inline]] inline Float8 vmax(Float8 a, Float8 b) { return select(a > b, a, b); }
[[gnu::always_inline]] inline Float8 vabs(Float8 a) {
  return Float8(reinterpret_cast<Float8Lanes>(reinterpret_cast<Mask8Lanes>(a.v) & (Mask8Lanes{} + 0x7fffffff)));
}
[[gnu::always_inline]] inline Float8 vsqrt(Float8 a) {
#if defined(__AVX__)
  return Float8(_mm256_sqrt_ps(a.v));
#elif defined(__SSE2__)
  // Two SSE halves: the compiler may join them where the caller has AVX.
  const __m128 lo = _mm_sqrt_ps(__builtin_shufflevector(a.v, a.v, 0, 1, 2, 3));
  const __m128 hi = _mm_sqrt_ps(__builtin_shufflevector(a.v, a.v, 4, 5, 6, 7));
  return Float8(__builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7));
#else
  Float8 r;
  for (int k = 0; k < 8; ++k) r.v[k] = std::sqrt(a.v[k]);
  return r;
#endif
}

}  // namespace prism
