// lanes::SphericalTriangle8: core/spherical_triangle.h's solid angle and uniform sampling (Arvo 1995) for eight lanes.
#pragma once

#include "core/sampling.h"
#include "core/spherical_triangle.h"
#include "integrators/lane_math.h"

namespace prism::lanes {

// SphericalTriangle::Corner for eight lanes.
struct Corner8 {
  V8 p, dir;
  F8 distance, inverse_distance;
};

// SphericalTriangle::see.
[[gnu::always_inline]] inline Corner8 see(const V8& ref, const V8& p) {
  Corner8 c;
  c.p = p;
  const V8 d = sub(p, ref);
  c.distance = root(dot(d, d));
  c.inverse_distance = pick(c.distance > 0, splat(1.0f) / c.distance, splat(0.0f));
  c.dir = mul(d, c.inverse_distance);
  return c;
}

// SphericalTriangle::solid_angle: the solid angle alone, with its operations in the same order.
[[gnu::always_inline]] inline F8 solid_angle(const Corner8& c0, const Corner8& c1, const Corner8& c2) {
  const M8 seen = (c0.distance > 0) & (c1.distance > 0) & (c2.distance > 0);
  const F8 det =
      dot(c0.dir, cross(mul(sub(c1.p, c0.p), c1.inverse_distance), mul(sub(c2.p, c0.p), c2.inverse_distance)));
  const F8 ab = dot(c0.dir, c1.dir), bc = dot(c1.dir, c2.dir), ca = dot(c2.dir, c0.dir);
  const F8 omega = splat(2.0f) * atan2_fast(absolute(det), splat(1.0f) + ab + bc + ca);
  return pick(seen & (absolute(omega) <= std::numeric_limits<float>::max()), omega, splat(0.0f));
}

// A SphericalTriangle's members, lane by lane (all zero where ref is on a corner, as there).
struct SphericalTriangle8 {
  V8 a, b, c, e1, e2, o;
  F8 det, solid_angle;
};

// SphericalTriangle's constructor from three corners, with its operations in the same order.
[[gnu::always_inline]] inline SphericalTriangle8 spherical_triangle(const V8& ref, const Corner8& c0, const Corner8& c1,
                                                                    const Corner8& c2) {
  const M8 seen = (c0.distance > 0) & (c1.distance > 0) & (c2.distance > 0);
  SphericalTriangle8 t;
  t.a = c0.dir;
  t.b = c1.dir;
  t.c = c2.dir;
  const V8 e1 = sub(c1.p, c0.p), e2 = sub(c2.p, c0.p);
  const F8 scale = splat(1.0f) / maximum(maximum(c0.distance, c1.distance), c2.distance);  // std::max({l0, l1, l2})
  t.e1 = mul(e1, scale);
  t.e2 = mul(e2, scale);
  t.o = mul(sub(ref, c0.p), scale);
  t.det = dot(t.a, cross(mul(e1, c1.inverse_distance), mul(e2, c2.inverse_distance)));
  const F8 ab = dot(t.a, t.b), bc = dot(t.b, t.c), ca = dot(t.c, t.a);
  const F8 denominator = splat(1.0f) + ab + bc + ca;
  t.solid_angle = splat(2.0f) * atan2_fast(absolute(t.det), denominator);
  t.solid_angle = pick(absolute(t.solid_angle) <= std::numeric_limits<float>::max(), t.solid_angle, splat(0.0f));
  // The relabelling of the corners seen furthest apart (SphericalTriangle::kRelabelCos).
  constexpr float kCos = SphericalTriangle::kRelabelCos;
  const M8 ab_apart = (ab < kCos) & (ab < bc) & (ab <= ca);
  const M8 ca_apart = ~ab_apart & (ca < kCos) & (ca < bc) & (ca < ab);
  const V8 a = t.a, b = t.b, c = t.c;
  t.a = pick(ab_apart, c, pick(ca_apart, b, a));
  t.b = pick(ab_apart, a, pick(ca_apart, c, b));
  t.c = pick(ab_apart, b, pick(ca_apart, a, c));
  // Ref on a corner: the constructor returns before setting any member.
  const V8 zero{};
  for (V8* v : {&t.a, &t.b, &t.c, &t.e1, &t.e2, &t.o}) *v = pick(seen, *v, zero);
  t.det = pick(seen, t.det, splat(0.0f));
  t.solid_angle = pick(seen, t.solid_angle, splat(0.0f));
  return t;
}

// Lane by lane, triangle x where m is set, else y.
[[gnu::always_inline]] inline SphericalTriangle8 pick(M8 m, const SphericalTriangle8& x, const SphericalTriangle8& y) {
  return {pick(m, x.a, y.a),   pick(m, x.b, y.b),   pick(m, x.c, y.c),           pick(m, x.e1, y.e1),
          pick(m, x.e2, y.e2), pick(m, x.o, y.o),   pick(m, x.det, y.det), pick(m, x.solid_angle, y.solid_angle)};
}

// SphericalTriangle::sample's barycentrics; `drawn` false where it gives none.
struct Barycentrics8 {
  F8 b0, b1, b2;
  M8 drawn;
};

// SphericalTriangle::sample, with its operations in the same order.
[[gnu::always_inline]] inline Barycentrics8 sample(const SphericalTriangle8& tri, F8 ux, F8 uy) {
  const V8 n_ac = cross(tri.a, tri.c);
  const F8 sin_ac = root(dot(n_ac, n_ac));
  M8 drawn = (sin_ac > 0) & (tri.solid_angle > 0);
  const V8 t = mul(cross(n_ac, tri.a), splat(1.0f) / sin_ac);
  const F8 det_t = absolute(tri.det) / sin_ac;
  F8 sin_half, cos_half;
  sin_cos_half_turn_of(splat(0.5f) * ux * tri.solid_angle, sin_half, cos_half,
                       [](M8 m, F8 x, F8 y) { return pick(m, x, y); });
  const F8 tau_divisor = cos_half * det_t - sin_half * dot(tri.b, t);
  const F8 tau = sin_half * (splat(1.0f) + dot(tri.a, tri.b)) / tau_divisor;
  const F8 inv = splat(1.0f) / (splat(1.0f) + tau * tau);
  const V8 c_sub = pick((tau_divisor > 0) & (tau < 1e18f),
                        add(mul(tri.a, (splat(1.0f) - tau * tau) * inv), mul(t, splat(2.0f) * tau * inv)), tri.c);
  const V8 chord = sub(c_sub, tri.b);
  const F8 one_minus_cos = splat(0.5f) * dot(chord, chord);
  const F8 one_minus_z = uy * one_minus_cos;
  const V8 across = add(chord, mul(tri.b, one_minus_cos));
  const F8 across_length = root(dot(across, across));
  const F8 sin_z = root(maximum(splat(0.0f), one_minus_z * (splat(2.0f) - one_minus_z)));
  const V8 w = pick(across_length > 0,
                    add(mul(tri.b, splat(1.0f) - one_minus_z), mul(across, sin_z / across_length)), tri.b);
  const V8 normal = cross(tri.e1, tri.e2);
  const F8 facing = dot(w, normal);
  drawn &= facing != 0;
  const V8 q = add(tri.o, mul(w, -dot(tri.o, normal) / facing));
  const F8 inv_normal2 = splat(1.0f) / dot(normal, normal);
  Barycentrics8 out;
  F8 b1 = maximum(splat(0.0f), dot(cross(q, tri.e2), normal) * inv_normal2);
  F8 b2 = maximum(splat(0.0f), dot(cross(tri.e1, q), normal) * inv_normal2);
  const F8 sum = b1 + b2;
  const M8 outside = sum > 1;
  b1 = pick(outside, b1 / sum, b1);
  b2 = pick(outside, b2 / sum, b2);
  out.b0 = splat(1.0f) - b1 - b2;
  out.b1 = b1;
  out.b2 = b2;
  out.drawn = drawn;
  return out;
}

}  // namespace prism::lanes
