// atan2 for hot paths: a few float operations inline, within 3 ulp of the exact angle.
#pragma once

#include <cmath>

#include "core/constants.h"

namespace prism {

// The pieces atan2_fast shares with its SIMD form (lanes::atan2_fast).
namespace atan2_parts {
constexpr float kTanPiOver8 = 0.41421356f;
// pi / 4, pi / 2 and pi as the nearest float plus what it misses, so that sums near them keep
// their last bits (without the low parts the error reached 2.9 ulp).
constexpr float kQuarterPiLow = -2.1855695e-8f, kHalfPiLow = -4.3711390e-8f, kPiLow = -8.7422777e-8f;
// atan t for |t| <= tan(pi / 8), for one value or (T a vector of floats) for eight lanes'
// (integrators/lane_math.h): each float constant stands for its value in every lane.
template <class T>
[[gnu::always_inline]] inline T atan_reduced(T t) {
  const T s = t * t;
  const T p = -0.33333331813536693f +
              s * (0.19999550085353582f +
                   s * (-0.14264232755088999f + s * (0.10746300025628576f + s * -0.06459380440346921f)));
  return t + t * s * p;
}
}  // namespace atan2_parts

// atan2(y, x) in (-pi, pi], as std::atan2 for finite inputs (both infinite: pi / 4 in the
// quadrant; a NaN gives NaN). The ratio of the smaller to the larger magnitude is reduced to
// |t| <= tan(pi / 8) (atan a = pi / 4 + atan((a - 1) / (a + 1)) above it), where
// atan t = t + t s P(s), s = t^2, with P of degree 4 fitted by least squares on Chebyshev nodes
// (relative error 2.6e-9 in double, under float rounding; with the rounding of the ratios, at most
// 2.5 ulp in tests/test_arctangent.cpp). The glibc call it replaces costs about
// 60 instructions across three functions (callgrind); this is about 25.
inline float atan2_fast(float y, float x) {
  using namespace atan2_parts;
  if (std::isnan(x) || std::isnan(y)) return x + y;
  const float ax = std::abs(x), ay = std::abs(y);
  const float hi = std::max(ax, ay), lo = std::min(ax, ay);
  float a = hi > 0 ? lo / hi : 0.0f;  // in [0, 1]
  if (std::isnan(a)) a = 1;           // both infinite
  const bool reduced = a > kTanPiOver8;
  float r = atan_reduced(reduced ? (a - 1) / (a + 1) : a);
  if (reduced) r = kPi / 4 + (r + kQuarterPiLow);
  if (ay > ax) r = kPi / 2 - (r - kHalfPiLow);
  if (x < 0 || (x == 0 && std::signbit(x))) r = kPi - (r - kPiLow);
  return std::copysign(r, y);
}

}  // namespace prism
