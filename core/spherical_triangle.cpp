#include "core/spherical_triangle.h"

#include <algorithm>
#include <cmath>

namespace prism {
namespace {

// The unit vector along the part of v orthogonal to unit w (a Gram-Schmidt step).
inline Vec3 orthogonal_unit(const Vec3& v, const Vec3& w) {
  const Vec3 o = v - w * dot(v, w);
  const float len2 = length_squared(o);
  return len2 > 0 ? o * (1.0f / std::sqrt(len2)) : Vec3{};
}

}  // namespace

SphericalTriangle::SphericalTriangle(const Vec3& ref, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const Vec3 d0 = p0 - ref, d1 = p1 - ref, d2 = p2 - ref;
  const float l0 = length(d0), l1 = length(d1), l2 = length(d2);
  if (!(l0 > 0 && l1 > 0 && l2 > 0)) return;  // ref on a corner
  // Every vector is scaled by reciprocals of single distances, never of a product of them: the
  // product of three distances overflows a float beyond ~1e12 and underflows below ~1e-12.
  const float r0 = 1.0f / l0, r1 = 1.0f / l1, r2 = 1.0f / l2;
  a_ = d0 * r0;
  b_ = d1 * r1;
  c_ = d2 * r2;
  // The plane intersection in sample() is invariant to a common scale of its three vectors: scaled
  // by the longest distance, they stay within [-2, 2].
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  const float scale = 1.0f / std::max({l0, l1, l2});
  e1_ = e1 * scale;
  e2_ = e2 * scale;
  o_ = (ref - p0) * scale;
  // The triple product of the corner directions is d0 . (e1 x e2) / (l0 l1 l2): no cancellation
  // between the long vectors of a far, small triangle. |e1| / l1 <= 1 + l0 / l1, so each factor
  // stays in range unless the distances differ by ~1e19.
  det_ = dot(a_, cross(e1 * r1, e2 * r2));
  // Van Oosterom and Strackee (IEEE TBME 1983): tan(omega / 2) = |a . (b x c)| / (1 + a.b + b.c + c.a).
  const float denominator = 1.0f + dot(a_, b_) + dot(b_, c_) + dot(c_, a_);
  solid_angle_ = 2.0f * std::atan2(std::abs(det_), denominator);
  if (!std::isfinite(solid_angle_)) solid_angle_ = 0;
}

std::optional<Barycentrics> SphericalTriangle::sample(Vec2 u) const {
  // Arvo 1995: choose the sub-triangle (a, b, c') whose area is u.x of the whole, with c' on the
  // arc from a to c, then a point on the arc from b to c' so that the result is uniform.
  const Vec3 n_ab = cross(a_, b_), n_ac = cross(a_, c_);
  const float len_ab = length(n_ab), len_ac = length(n_ac);
  if (!(len_ab > 0 && len_ac > 0 && solid_angle_ > 0)) return std::nullopt;
  const float inv_lengths = 1.0f / (len_ab * len_ac);
  // The angle alpha at corner a lies between the planes (a, b) and (a, c); its sine follows from
  // (a x b) x (a x c) = (a . (b x c)) a.
  const float cos_alpha = dot(n_ab, n_ac) * inv_lengths;
  const float sin_alpha = std::abs(det_) * inv_lengths;
  const float area = u.x * solid_angle_;
  float sin_area, cos_area;
  sincosf(area, &sin_area, &cos_area);
  const float s = sin_area * cos_alpha - cos_area * sin_alpha;  // sin(area - alpha)
  const float t = cos_area * cos_alpha + sin_area * sin_alpha;  // cos(area - alpha)
  const float uu = t - cos_alpha;
  const float v = s + sin_alpha * dot(a_, b_);
  // cos of the arc from a to c' (Arvo's q).
  const float q = std::clamp(((v * t - uu * s) * cos_alpha - v) / ((v * s + uu * t) * sin_alpha), -1.0f, 1.0f);
  // c - (c . a) a = (a x c) x a, of length |a x c|.
  const Vec3 c_across = cross(n_ac, a_) * (1.0f / len_ac);
  const Vec3 c_sub = a_ * q + c_across * std::sqrt(std::max(0.0f, 1.0f - q * q));
  const float z = 1.0f - u.y * (1.0f - dot(c_sub, b_));
  const Vec3 w = b_ * z + orthogonal_unit(c_sub, b_) * std::sqrt(std::max(0.0f, 1.0f - z * z));
  // Where the ray ref + s w meets the triangle's plane (Moller and Trumbore, JGT 1997).
  const Vec3 s1 = cross(w, e2_);
  const float divisor = dot(s1, e1_);
  if (!(divisor != 0)) return std::nullopt;
  const float inv_divisor = 1.0f / divisor;
  float b1 = std::max(0.0f, dot(o_, s1) * inv_divisor);
  float b2 = std::max(0.0f, dot(w, cross(o_, e1_)) * inv_divisor);
  if (b1 + b2 > 1) {  // rounding put the point just outside
    const float sum = b1 + b2;
    b1 /= sum;
    b2 /= sum;
  }
  return Barycentrics{1.0f - b1 - b2, b1, b2};
}

}  // namespace prism
