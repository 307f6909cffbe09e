// Warping functions from uniform samples in [0,1)^n to directions and points, with their pdfs.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/constants.h"
#include "core/vec3.h"

namespace prism {

// sin and cos of |a| <= pi/4 by their Taylor series to a^9 and a^10 (truncation below 2e-9, so
// within a couple of float ulps): on this range they need no argument reduction, which is most
// of what libm's sincosf spends.
struct SinCos {
  float sin, cos;
};
// The polynomials for one angle (T float) or for eight lanes' (T a vector of floats, as
// integrators/lane_bounce.h takes it): each float constant stands for its value in every lane,
// so every lane gets the bits the float form gives.
template <class T>
[[gnu::always_inline]] inline void sin_cos_quarter_of(T a, T& s, T& c) {
  const T a2 = a * a;
  s = a * (1.0f + a2 * (-1.0f / 6 + a2 * (1.0f / 120 + a2 * (-1.0f / 5040 + a2 * (1.0f / 362880)))));
  c = 1.0f + a2 * (-0.5f + a2 * (1.0f / 24 + a2 * (-1.0f / 720 + a2 * (1.0f / 40320 + a2 * (-1.0f / 3628800)))));
}
inline SinCos sin_cos_quarter(float a) {
  SinCos sc;
  sin_cos_quarter_of(a, sc.sin, sc.cos);
  return sc;
}

// sin and cos of 0 <= a <= pi: a less the nearest multiple k of pi/2 (Cody and Waite's reduction:
// pi/2 as a float plus what it misses; a - k x that float is exact by Sterbenz's lemma) is within
// pi/4, where sin_cos_quarter_of holds, and k turns the result by quarter turns. `pick(m, x, y)` is
// m ? x : y, for one angle or (with masks) for eight lanes' (integrators/lane_spherical_triangle.h).
template <class T, class Pick>
[[gnu::always_inline]] inline void sin_cos_half_turn_of(T a, T& s, T& c, Pick pick) {
  constexpr float kPiOver2Low = -4.371139e-8f;  // pi/2 - kPiOver2
  const auto second = a > 0.75f * kPi, first = a > kPiOver4;
  const T k = pick(second, T{} + 2.0f, pick(first, T{} + 1.0f, T{} + 0.0f));
  T sr, cr;
  sin_cos_quarter_of((a - k * kPiOver2) - k * kPiOver2Low, sr, cr);
  s = pick(second, -sr, pick(first, cr, sr));
  c = pick(second, -cr, pick(first, -sr, cr));
}
inline SinCos sin_cos_half_turn(float a) {
  SinCos sc;
  sin_cos_half_turn_of(a, sc.sin, sc.cos, [](bool m, float x, float y) { return m ? x : y; });
  return sc;
}

// Concentric square-to-disk map (Shirley and Chiu, "A Low Distortion Map Between Disk and
// Square", JGT 1997): keeps stratification. The angle is pi/4 x (a ratio in [-1, 1]), or pi/2
// minus that, so sin and cos come from sin_cos_quarter.
inline Vec2 sample_uniform_disk_concentric(Vec2 u) {
  const float ox = 2.0f * u.x - 1.0f, oy = 2.0f * u.y - 1.0f;
  if (ox == 0 && oy == 0) return {0, 0};
  if (std::abs(ox) > std::abs(oy)) {
    const SinCos sc = sin_cos_quarter(kPiOver4 * (oy / ox));
    return {ox * sc.cos, ox * sc.sin};
  }
  const SinCos sc = sin_cos_quarter(kPiOver4 * (ox / oy));  // theta = pi/2 - this angle
  return {oy * sc.sin, oy * sc.cos};
}

// Cosine-weighted hemisphere around +z (Malley's method); pdf = cos(theta) / pi.
inline Vec3 sample_cosine_hemisphere(Vec2 u) {
  const Vec2 d = sample_uniform_disk_concentric(u);
  const float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return std::max(cos_theta, 0.0f) * kInvPi; }

// Uniform direction on the unit sphere; pdf = 1 / (4 pi).
inline Vec3 sample_uniform_sphere(Vec2 u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = kTwoPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Uniform direction inside the cone of half-angle acos(cos_max) around +z;
// pdf = 1 / (2 pi (1 - cos_max)). `one_minus_cos_max` is passed separately so tiny cones keep
// their precision (1 - cos underflows for small angles).
inline Vec3 sample_uniform_cone(Vec2 u, float one_minus_cos_max) {
  const float one_minus_cos = u.x * one_minus_cos_max;
  const float cos_theta = 1.0f - one_minus_cos;
  // sin^2 = (1 - cos)(1 + cos), exact for small angles.
  const float sin_theta = std::sqrt(std::max(0.0f, one_minus_cos * (2.0f - one_minus_cos)));
  const float phi = kTwoPi * u.y;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

// Uniform barycentrics (b0, b1) on a triangle (the square-root parameterisation); the third
// is 1 - b0 - b1; pdf = 1 / area.
inline Vec2 sample_uniform_triangle(Vec2 u) {
  const float su = std::sqrt(u.x);
  return {1.0f - su, u.y * su};
}

// Veach's power heuristic with beta = 2 for two strategies taking one sample each.
inline float power_heuristic(float pdf_a, float pdf_b) {
  const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  if (std::isinf(a)) return 1.0f;
  return a + b > 0 ? a / (a + b) : 0.0f;
}

}  // namespace prism
