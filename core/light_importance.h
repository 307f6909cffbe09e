// LightImportance: how much a group of lights can light a shading point, judged from its bounds, for
// one group or four side by side in SIMD lanes (a light tree node's children).
#pragma once

#include "core/float4.h"
#include "core/float8.h"
#include "core/light_bounds.h"
#include "core/vec3.h"

namespace prism {

// LightBounds reduced to what judging it from a point needs, precomputed, in lanes of type F
// (float for one group, Float4 for four, Float8 for eight).
template <class F>
struct ImportanceTerms {
  F center_x, center_y, center_z;  // of the box
  F radius;                        // of the box's bounding sphere
  F axis_x{0.0f}, axis_y{0.0f}, axis_z{1.0f};
  F cos_o{1.0f}, sin_o{0.0f};  // the normals' cone
  F cos_emit;
  F two_sided;    // 1: emits along -normal too; 0: not
  F inv_radius2;  // 1 / max(radius^2, FLT_MIN): the inverse square's cap
  F power;        // scaled by the tree's power_scale
};

// op(out.t, in.t...) for every term t, the same term of every argument together.
template <class Op, class Out, class... In>
void for_each_term(Op op, Out& out, const In&... in) {
  op(out.center_x, in.center_x...);
  op(out.center_y, in.center_y...);
  op(out.center_z, in.center_z...);
  op(out.radius, in.radius...);
  op(out.axis_x, in.axis_x...);
  op(out.axis_y, in.axis_y...);
  op(out.axis_z, in.axis_z...);
  op(out.cos_o, in.cos_o...);
  op(out.sin_o, in.sin_o...);
  op(out.cos_emit, in.cos_emit...);
  op(out.two_sided, in.two_sided...);
  op(out.inv_radius2, in.inv_radius2...);
  op(out.power, in.power...);
}

// An estimate of the light the group sends to point p whose surface has unit normal n (zero: no
// surface), from bounds on the emission and incidence angles over the whole group: power x
// cos(theta') x cos(theta_i') / d^2 (Conty Estevez & Kulla 2018, eq. 3). It is 0 only where no
// point of the group can light p's surface (or where it is below float range, a 1e-38 share of a
// tree's light), so choosing groups in proportion to it misses nothing. Branch-free, so that four
// groups take one pass of SIMD lanes; the scalar form computes the same bits.
template <class F>
F importance_at(const ImportanceTerms<F>& g, const Vec3& p, const Vec3& n) {
  const F zero(0.0f), one(1.0f);
  // cos(max(0, a - b)) from the cosines and sines of a and b, both in [0, pi].
  auto cos_minus_clamped = [&](F cos_a, F sin_a, F cos_b, F sin_b) {
    return select(cos_a >= cos_b, one, cos_a * cos_b + sin_a * sin_b);
  };
  auto safe_sqrt = [&](F x) { return vsqrt(vmax(x, zero)); };

  const F dx = F(p.x) - g.center_x, dy = F(p.y) - g.center_y, dz = F(p.z) - g.center_z;
  const F dist2 = dx * dx + dy * dy + dz * dz;
  const auto apart = dist2 > zero;
  const F inv_dist = select(apart, one / vsqrt(dist2), zero);
  // wi: from the group toward p.
  const F wx = select(apart, dx * inv_dist, zero), wy = select(apart, dy * inv_dist, zero),
          wz = select(apart, dz * inv_dist, one);
  // The box's bounding sphere seen from p subtends directions within theta_b of -wi; from inside
  // it, every direction.
  const auto outside = dist2 > g.radius * g.radius;
  const F sin_b = select(outside, g.radius * inv_dist, zero);
  const F cos_b = select(outside, safe_sqrt(one - sin_b * sin_b), F(-1.0f));

  // theta' = theta_w - theta_o - theta_b: the smallest angle, from a normal of the group, at which
  // any of its points can see p; past cos_emit no point can.
  F cos_w = g.axis_x * wx + g.axis_y * wy + g.axis_z * wz;
  cos_w = select(g.two_sided > zero, vabs(cos_w), cos_w);
  const auto off_axis = cos_w < g.cos_o;
  const F sin_w = safe_sqrt(one - cos_w * cos_w);
  const F cos_x = cos_w * g.cos_o + sin_w * g.sin_o;  // theta_w - theta_o > 0 where off_axis
  const F sin_x = sin_w * g.cos_o - cos_w * g.sin_o;
  const F cos_emission = select(off_axis, cos_minus_clamped(cos_x, sin_x, cos_b, sin_b), one);
  const auto unseen = both(off_axis, cos_emission < g.cos_emit);
  // The receiving cosine, bounded the same way; |cos| because a surface may transmit.
  F cos_receive = one;
  if (n.x != 0 || n.y != 0 || n.z != 0) {
    const F cos_i = vabs(F(n.x) * wx + F(n.y) * wy + F(n.z) * wz);
    cos_receive = cos_minus_clamped(cos_i, safe_sqrt(one - cos_i * cos_i), cos_b, sin_b);
  }
  // Closer than the bounding radius the inverse square means nothing: the group is all around.
  const F inv_d2 = select(apart, vmin(inv_dist * inv_dist, g.inv_radius2), g.inv_radius2);
  return select(unseen, zero, g.power * vmax(cos_emission, zero) * cos_receive * inv_d2);
}

// One group's terms.
class LightImportance {
 public:
  LightImportance() = default;  // no power: importance 0 everywhere
  // power_scale divides the power, to keep importance within float range (1 / the tree's total).
  LightImportance(const LightBounds& b, double power_scale);

  float operator()(const Vec3& p, const Vec3& n) const { return importance_at(terms_, p, n); }
  float power() const { return terms_.power; }
  const ImportanceTerms<float>& terms() const { return terms_; }

 private:
  ImportanceTerms<float> terms_{};
};

// Four groups judged at once; lane k gives what the LightImportance set there gives, bit for bit.
class LightImportance4 {
 public:
  LightImportance4() = default;  // every lane as LightImportance(): no power
  void set(int lane, const LightImportance& group);
  void evaluate(const Vec3& p, const Vec3& n, float out[4]) const { importance_at(terms_, p, n).store(out); }
  const ImportanceTerms<Float4>& terms() const { return terms_; }

 private:
  ImportanceTerms<Float4> terms_;
};

// Two LightImportance4 judged at once in eight AVX lanes: out[0..3] are what lo.evaluate gives and
// out[4..7] what hi.evaluate gives, bit for bit, in about half the instructions of the two calls.
// Returns their sum added pairwise, ((o0 + o1) + (o2 + o3)) + ((o4 + o5) + (o6 + o7)). Call only
// where cpu_has_avx2().
float evaluate_pair(const LightImportance4& lo, const LightImportance4& hi, const Vec3& p, const Vec3& n,
                    float out[8]);

}  // namespace prism
