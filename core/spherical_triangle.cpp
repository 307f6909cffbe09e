#include "core/spherical_triangle.h"

#include <algorithm>
#include <cmath>

#include "core/arctangent.h"
#include "core/sampling.h"

namespace prism {

SphericalTriangle::SphericalTriangle(const Vec3& ref, const Vec3& p0, const Vec3& p1, const Vec3& p2)
    : SphericalTriangle(ref, see(ref, p0), see(ref, p1), see(ref, p2)) {}

// The triple product of the corner directions is d0 . (e1 x e2) / (l0 l1 l2): no cancellation
// between the long vectors of a far, small triangle. |e1| / l1 <= 1 + l0 / l1, so each factor
// stays in range unless the distances differ by ~1e19.
float SphericalTriangle::triple_product(const Corner& c0, const Corner& c1, const Corner& c2) {
  return dot(c0.dir, cross((c1.p - c0.p) * c1.inverse_distance, (c2.p - c0.p) * c2.inverse_distance));
}

// Van Oosterom and Strackee (IEEE TBME 1983): tan(omega / 2) = |a . (b x c)| / (1 + a.b + b.c + c.a).
float SphericalTriangle::solid_angle_from(float det, float ab, float bc, float ca) {
  const float denominator = 1.0f + ab + bc + ca;
  const float omega = 2.0f * atan2_fast(std::abs(det), denominator);
  return std::isfinite(omega) ? omega : 0.0f;
}

float SphericalTriangle::solid_angle(const Corner& c0, const Corner& c1, const Corner& c2) {
  if (!(c0.distance > 0 && c1.distance > 0 && c2.distance > 0)) return 0;  // ref on a corner
  return solid_angle_from(triple_product(c0, c1, c2), dot(c0.dir, c1.dir), dot(c1.dir, c2.dir), dot(c2.dir, c0.dir));
}

// Every vector is scaled by reciprocals of single distances (Corner), never of a product of them:
// the product of three distances overflows a float beyond ~1e12 and underflows below ~1e-12.
SphericalTriangle::SphericalTriangle(const Vec3& ref, const Corner& c0, const Corner& c1, const Corner& c2) {
  set(ref, c0, c1, c2, -1.0f);
}

SphericalTriangle::SphericalTriangle(const Vec3& ref, const Corner& c0, const Corner& c1, const Corner& c2,
                                     float known_solid_angle) {
  set(ref, c0, c1, c2, known_solid_angle);
}

void SphericalTriangle::set(const Vec3& ref, const Corner& c0, const Corner& c1, const Corner& c2, float known) {
  const float l0 = c0.distance, l1 = c1.distance, l2 = c2.distance;
  if (!(l0 > 0 && l1 > 0 && l2 > 0)) return;  // ref on a corner
  a_ = c0.dir;
  b_ = c1.dir;
  c_ = c2.dir;
  // The plane intersection in sample() is invariant to a common scale of its three vectors: scaled
  // by the longest distance, they stay within [-2, 2].
  const Vec3 e1 = c1.p - c0.p, e2 = c2.p - c0.p;
  const float scale = 1.0f / std::max({l0, l1, l2});
  e1_ = e1 * scale;
  e2_ = e2 * scale;
  o_ = (ref - c0.p) * scale;
  det_ = triple_product(c0, c1, c2);
  const float ab = dot(a_, b_), bc = dot(b_, c_), ca = dot(c_, a_);
  solid_angle_ = known >= 0 ? known : solid_angle_from(det_, ab, bc, ca);
  // sample() divides by 1 + a.b and draws along the arcs from a to c and from b: in a triangle that
  // fills nearly a hemisphere two corners are seen nearly opposite, and that pair must be (b, c),
  // the one it never uses (with a and b opposite, an emitter 10000 wide seen from 2 away drew its
  // mean cosine 57% off). A cyclic relabelling keeps the triple product; the barycentrics come from
  // the plane, not from the labels. It is made only where a pair is over 120 degrees apart.
  if (ab < kRelabelCos && ab < bc && ab <= ca) {
    const Vec3 a = a_;
    a_ = c_;
    c_ = b_;
    b_ = a;
  } else if (ca < kRelabelCos && ca < bc && ca < ab) {
    const Vec3 a = a_;
    a_ = b_;
    b_ = c_;
    c_ = a;
  }
}

std::optional<Barycentrics> SphericalTriangle::sample(Vec2 u) const {
  // Arvo 1995: choose the sub-triangle (a, b, c') whose solid angle is u.x of the whole, with c' on
  // the arc from a to c, then a point on the arc from b to c' so that the result is uniform.
  // Arvo finds c' through the angles of the triangle (cos q = ...) and the point through 1 - cos;
  // both cancel catastrophically in float for slivers and grazing views (u came back off by 1e-3 to
  // 1e-2, SphericalTriangleExtremes). Here c' comes from the solid-angle formula itself, and the
  // point from chords, which do not cancel.
  const Vec3 n_ac = cross(a_, c_);
  const float sin_ac = length(n_ac);
  if (!(sin_ac > 0 && solid_angle_ > 0)) return std::nullopt;
  // c' = a cos phi + t sin phi, t the unit tangent at a toward c. With it a.(b x c') = sin phi a.(b x t),
  // a.c' = cos phi and b.c' = cos phi a.b + sin phi b.t, so Van Oosterom and Strackee's
  // tan(omega'/2) (1 + a.b + b.c' + c'.a) = |a.(b x c')|, with tau = tan(phi / 2), is linear in tau:
  //   tau (cos(omega'/2) |a.(b x t)| - sin(omega'/2) b.t) = sin(omega'/2) (1 + a.b).
  const Vec3 t = cross(n_ac, a_) * (1.0f / sin_ac);
  const float det_t = std::abs(det_) / sin_ac;  // |a . (b x t)|
  // omega' / 2 is within [0, pi]: sin_cos_half_turn, which SIMD lanes can take as well.
  const SinCos half = sin_cos_half_turn(0.5f * u.x * solid_angle_);
  const float sin_half = half.sin, cos_half = half.cos;
  const float tau_divisor = cos_half * det_t - sin_half * dot(b_, t);
  const float tau = sin_half * (1.0f + dot(a_, b_)) / tau_divisor;
  Vec3 c_sub = c_;  // phi passes the arc's end only by rounding: stop there
  if (tau_divisor > 0 && tau < 1e18f) {
    const float inv = 1.0f / (1.0f + tau * tau);
    c_sub = a_ * ((1.0f - tau * tau) * inv) + t * (2.0f * tau * inv);
  }
  // The point w on the arc from b to c' at 1 - w.b = u.y (1 - c'.b), where 1 - c'.b is half the
  // chord squared; the part of c' across b is the chord plus b times that, so nothing cancels.
  const Vec3 chord = c_sub - b_;
  const float one_minus_cos = 0.5f * dot(chord, chord);  // 1 - c'.b
  const float one_minus_z = u.y * one_minus_cos;
  const Vec3 across = chord + b_ * one_minus_cos;
  const float across_length = length(across);
  const float sin_z = std::sqrt(std::max(0.0f, one_minus_z * (2.0f - one_minus_z)));
  const Vec3 w = across_length > 0 ? b_ * (1.0f - one_minus_z) + across * (sin_z / across_length) : b_;
  // Where the ray ref + s w meets the triangle's plane. Seen at a grazing angle, the distance s is
  // uncertain, but only along w, which leaves the direction to the point as it is; Moller and
  // Trumbore's barycentrics, by contrast, lose precision across w as well.
  const Vec3 normal = cross(e1_, e2_);
  const float facing = dot(w, normal);
  if (!(facing != 0)) return std::nullopt;
  const Vec3 q = o_ + w * (-dot(o_, normal) / facing);  // the point - p0, scaled
  const float inv_normal2 = 1.0f / length_squared(normal);
  float b1 = std::max(0.0f, dot(cross(q, e2_), normal) * inv_normal2);
  float b2 = std::max(0.0f, dot(cross(e1_, q), normal) * inv_normal2);
  if (b1 + b2 > 1) {  // rounding put the point just outside
    const float sum = b1 + b2;
    b1 /= sum;
    b2 /= sum;
  }
  return Barycentrics{1.0f - b1 - b2, b1, b2};
}

}  // namespace prism
