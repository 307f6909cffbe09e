// Warping functions from uniform samples in [0,1)^n to directions and points, with their pdfs.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/constants.h"
#include "core/vec3.h"

namespace prism {

// Concentric square-to-disk map (Shirley and Chiu, "A Low Distortion Map Between Disk and
// Square", JGT 1997): keeps stratification.
inline Vec2 sample_uniform_disk_concentric(Vec2 u) {
  const float ox = 2.0f * u.x - 1.0f, oy = 2.0f * u.y - 1.0f;
  if (ox == 0 && oy == 0) return {0, 0};
  float r, theta;
  if (std::abs(ox) > std::abs(oy)) {
    r = ox;
    theta = kPiOver4 * (oy / ox);
  } else {
    r = oy;
    theta = kPiOver2 - kPiOver4 * (ox / oy);
  }
  return {r * std::cos(theta), r * std::sin(theta)};
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
