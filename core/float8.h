// Float8: eight floats in one vector, with the operations Float4 has, so importance_at runs on eight lanes.
#pragma once

#include <cstdint>
#include <cstring>

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
// Eight consecutive floats as lanes 0-7, and back.
[[gnu::always_inline]] inline Float8 load8(const float* x) {
  Float8 r;
  std::memcpy(&r.v, x, sizeof(r.v));
  return r;
}
[[gnu::always_inline]] inline void store8(float* x, Float8 a) { std::memcpy(x, &a.v, sizeof(a.v)); }
// How many lanes of m hold.
[[gnu::always_inline]] inline int count_lanes(Mask8 m) {
#if defined(__SSE2__)
  const __m128 lo = reinterpret_cast<__m128>(__builtin_shufflevector(m.v, m.v, 0, 1, 2, 3));
  const __m128 hi = reinterpret_cast<__m128>(__builtin_shufflevector(m.v, m.v, 4, 5, 6, 7));
  return __builtin_popcount(unsigned(_mm_movemask_ps(lo)) | unsigned(_mm_movemask_ps(hi)) << 4);
#else
  int n = 0;
  for (int k = 0; k < 8; ++k) n += m.v[k] != 0;
  return n;
#endif
}
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

// Eight records' floats [offset, offset + 8) turned into rows of lanes: lane k of rows[j] is
// records[k][offset + j]. An 8x8 transpose in three rounds of shuffles.
[[gnu::always_inline]] inline void transpose(const float* const* records, int offset, Float8Lanes (&rows)[8]) {
  Float8Lanes a[8], t[8], u[8];
  for (int k = 0; k < 8; ++k) std::memcpy(&a[k], records[k] + offset, sizeof(Float8Lanes));
  for (int k = 0; k < 8; k += 2) {  // interleave lane pairs: fields (0, 1, 4, 5) and (2, 3, 6, 7)
    t[k] = __builtin_shufflevector(a[k], a[k + 1], 0, 8, 1, 9, 4, 12, 5, 13);
    t[k + 1] = __builtin_shufflevector(a[k], a[k + 1], 2, 10, 3, 11, 6, 14, 7, 15);
  }
  for (int k = 0; k < 8; k += 4) {  // then lane quads: one field per 128-bit half
    for (int h = 0; h < 2; ++h) {
      u[k + 2 * h] = __builtin_shufflevector(t[k + h], t[k + h + 2], 0, 1, 8, 9, 4, 5, 12, 13);
      u[k + 2 * h + 1] = __builtin_shufflevector(t[k + h], t[k + h + 2], 2, 3, 10, 11, 6, 7, 14, 15);
    }
  }
  for (int j = 0; j < 4; ++j) {  // the halves of lanes 0-3 and 4-7 joined
    rows[j] = __builtin_shufflevector(u[j], u[j + 4], 0, 1, 2, 3, 8, 9, 10, 11);
    rows[j + 4] = __builtin_shufflevector(u[j], u[j + 4], 4, 5, 6, 7, 12, 13, 14, 15);
  }
}

}  // namespace prism
