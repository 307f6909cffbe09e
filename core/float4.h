// Float4: four floats in SIMD lanes (SSE where the target has it, a plain array elsewhere), with the
// scalar forms of the same operations, so that one formula serves one value and four, bit for bit.
#pragma once

#include <cmath>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace prism {

// The operations below round exactly as their scalar forms (IEEE add, sub, mul, div, sqrt), and
// vmin/vmax/select are written so that the scalar forms pick the same operand as SSE's minps and
// maxps in every case, NaN and signed zeros included: a formula templated on the type gives lane k
// of its Float4 form the very bits its float form gives for lane k's inputs.
inline float vmin(float a, float b) { return a < b ? a : b; }
inline float vmax(float a, float b) { return a > b ? a : b; }
inline float vsqrt(float a) { return std::sqrt(a); }
inline float vabs(float a) { return std::abs(a); }
inline float select(bool mask, float a, float b) { return mask ? a : b; }
inline bool both(bool a, bool b) { return a && b; }

#if defined(__SSE2__)

struct Float4 {
  __m128 v;
  Float4() : v(_mm_setzero_ps()) {}
  explicit Float4(float x) : v(_mm_set1_ps(x)) {}
  explicit Float4(__m128 x) : v(x) {}
  void set_lane(int k, float x) {
    alignas(16) float lanes[4];
    _mm_store_ps(lanes, v);
    lanes[k] = x;
    v = _mm_load_ps(lanes);
  }
  void store(float* out) const { _mm_storeu_ps(out, v); }
};

// A lane mask: all bits set where a comparison held.
struct Mask4 {
  __m128 v;
};

inline Float4 operator+(Float4 a, Float4 b) { return Float4(_mm_add_ps(a.v, b.v)); }
inline Float4 operator-(Float4 a, Float4 b) { return Float4(_mm_sub_ps(a.v, b.v)); }
inline Float4 operator*(Float4 a, Float4 b) { return Float4(_mm_mul_ps(a.v, b.v)); }
inline Float4 operator/(Float4 a, Float4 b) { return Float4(_mm_div_ps(a.v, b.v)); }
inline Mask4 operator<(Float4 a, Float4 b) { return {_mm_cmplt_ps(a.v, b.v)}; }
inline Mask4 operator>(Float4 a, Float4 b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
inline Mask4 operator>=(Float4 a, Float4 b) { return {_mm_cmpge_ps(a.v, b.v)}; }
inline Mask4 both(Mask4 a, Mask4 b) { return {_mm_and_ps(a.v, b.v)}; }
inline Float4 vmin(Float4 a, Float4 b) { return Float4(_mm_min_ps(a.v, b.v)); }  // a < b ? a : b
inline Float4 vmax(Float4 a, Float4 b) { return Float4(_mm_max_ps(a.v, b.v)); }  // a > b ? a : b
inline Float4 vsqrt(Float4 a) { return Float4(_mm_sqrt_ps(a.v)); }
inline Float4 vabs(Float4 a) { return Float4(_mm_andnot_ps(_mm_set1_ps(-0.0f), a.v)); }
inline Float4 select(Mask4 m, Float4 a, Float4 b) {
  return Float4(_mm_or_ps(_mm_and_ps(m.v, a.v), _mm_andnot_ps(m.v, b.v)));
}

#else

struct Float4 {
  float v[4] = {};
  Float4() = default;
  explicit Float4(float x) : v{x, x, x, x} {}
  void set_lane(int k, float x) { v[k] = x; }
  void store(float* out) const {
    for (int k = 0; k < 4; ++k) out[k] = v[k];
  }
};

struct Mask4 {
  bool v[4];
};

template <class Op>
Float4 lanewise(Float4 a, Float4 b, Op op) {
  Float4 r;
  for (int k = 0; k < 4; ++k) r.v[k] = op(a.v[k], b.v[k]);
  return r;
}
template <class Op>
Mask4 compare(Float4 a, Float4 b, Op op) {
  Mask4 r;
  for (int k = 0; k < 4; ++k) r.v[k] = op(a.v[k], b.v[k]);
  return r;
}
inline Float4 operator+(Float4 a, Float4 b) { return lanewise(a, b, [](float x, float y) { return x + y; }); }
inline Float4 operator-(Float4 a, Float4 b) { return lanewise(a, b, [](float x, float y) { return x - y; }); }
inline Float4 operator*(Float4 a, Float4 b) { return lanewise(a, b, [](float x, float y) { return x * y; }); }
inline Float4 operator/(Float4 a, Float4 b) { return lanewise(a, b, [](float x, float y) { return x / y; }); }
inline Mask4 operator<(Float4 a, Float4 b) { return compare(a, b, [](float x, float y) { return x < y; }); }
inline Mask4 operator>(Float4 a, Float4 b) { return compare(a, b, [](float x, float y) { return x > y; }); }
inline Mask4 operator>=(Float4 a, Float4 b) { return compare(a, b, [](float x, float y) { return x >= y; }); }
inline Mask4 both(Mask4 a, Mask4 b) {
  for (int k = 0; k < 4; ++k) a.v[k] = a.v[k] && b.v[k];
  return a;
}
inline Float4 vmin(Float4 a, Float4 b) { return lanewise(a, b, [](float x, float y) { return vmin(x, y); }); }
inline Float4 vmax(Float4 a, Float4 b) { return lanewise(a, b, [](float x, float y) { return vmax(x, y); }); }
inline Float4 vsqrt(Float4 a) { return lanewise(a, a, [](float x, float) { return vsqrt(x); }); }
inline Float4 vabs(Float4 a) { return lanewise(a, a, [](float x, float) { return vabs(x); }); }
inline Float4 select(Mask4 m, Float4 a, Float4 b) {
  for (int k = 0; k < 4; ++k) a.v[k] = m.v[k] ? a.v[k] : b.v[k];
  return a;
}

#endif

}  // namespace prism
