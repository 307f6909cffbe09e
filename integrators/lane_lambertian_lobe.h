// LambertianSurface, lanes::lambertian_lobe: a Lambertian vertex as SIMD kernels take it, its lobe made in lanes.
#pragma once

#include <cstdint>
#include <limits>

#include "core/constants.h"
#include "core/vec3.h"
#include "integrators/lane_math.h"
#include "integrators/lane_rows.h"

namespace prism {

// A vertex whose BSDF is the Lambertian lobe alone (Bsdf::lambertian_only), as the lanes take it:
// the Bsdf constructor's inputs, so that no Bsdf is built for it.
struct LambertianSurface {
  Vec3 ns;  // the unit shading normal (shading_normal)
  Vec3 ng;  // the hit's unit geometric normal, on its front face
  Vec3 wo;  // unit, away from the surface
  Rgb f;    // albedo / pi (Lambertian::f)
};

// The rows a LambertianSurface and its hit's point take, first in each batch's fields; rows of three
// hold a vector's x, y and z.
struct LambertianSurfaceFields {
  enum Row { kNs = 0, kNg = 3, kWo = 6, kF = 9, kP = 12, kPError = 15, kSurfaceRows = 18 };
};

// A batch whose lanes are Lambertian vertices (LaneRows, its first rows LambertianSurfaceFields').
template <int kRows>
class LambertianLaneRows : public LaneRows<kRows> {
 protected:
  // A vertex's surface, point and the point's error bound, in a new lane: returns it.
  int add_surface(const LambertianSurface& surface, const Vec3& p, const Vec3& p_error) {
    using F = LambertianSurfaceFields;
    const int lane = this->next_lane();
    this->set(F::kNs, lane, surface.ns);
    this->set(F::kNg, lane, surface.ng);
    this->set(F::kWo, lane, surface.wo);
    this->set(F::kF, lane, surface.f);
    this->set(F::kP, lane, p);
    this->set(F::kPError, lane, p_error);
    return lane;
  }
};

namespace lanes {

[[gnu::always_inline]] inline V8 negate(const V8& a) { return {-a.x, -a.y, -a.z}; }

// The lobe as Bsdf's constructor leaves it for a Lambertian mixture: valid false where the Bsdf is
// not (wo on the surface's plane or below the shading hemisphere), which gives nothing then.
struct Lobe {
  V8 s, t, n;  // the frame about the normal cosines are taken about
  V8 ng;       // the geometric normal, mirrored to wo's side
  F8 wo_dot_ng, wo_z;
  M8 valid;
};

// Bsdf::Bsdf's frame for a two-sided surface (a Lambertian mixture transmits nothing), with its
// operations in the same order: the mirror to wo's side, the bend of the shading normal toward a
// grazing wo, and Frame::from_normal (Duff et al. 2017).
[[gnu::always_inline]] inline Lobe lambertian_lobe(const V8& ns, const V8& ng, const V8& wo) {
  Lobe l;
  const F8 side = dot(wo, ng);
  const M8 mirror = side < 0;
  l.ng = pick(mirror, negate(ng), ng);
  V8 n = pick(mirror, negate(ns), ns);
  n = pick(dot(n, l.ng) < 0, negate(n), n);
  l.wo_dot_ng = dot(wo, l.ng);
  const F8 s_side = pick(l.wo_dot_ng < 0, splat(-1.0f), splat(1.0f));
  const V8 n_side = mul(n, s_side);
  const F8 a_side = splat(0.9f) * absolute(side);
  const F8 threshold = pick(splat(0.01f) < a_side, splat(0.01f), a_side);  // std::min(a_side, 0.01f)
  const F8 wo_n = dot(wo, n_side);
  const V8 bent = add(n_side, mul(wo, threshold - wo_n));
  const F8 bent2 = dot(bent, bent);
  const M8 bend = (side != 0) & (wo_n < threshold) & (bent2 > 0);
  n = pick(bend, mul(mul(bent, splat(1.0f) / root(bent2)), s_side), n);
  // Frame::from_normal: sign = copysign(1, n.z).
  constexpr int32_t kSignBit = std::numeric_limits<int32_t>::min(), kOne = 0x3f800000;
  const F8 sign = reinterpret_cast<F8>((reinterpret_cast<M8>(n.z) & kSignBit) | kOne);
  const F8 a = splat(-1.0f) / (sign + n.z);
  const F8 b = n.x * n.y * a;
  l.s = {splat(1.0f) + sign * n.x * n.x * a, sign * b, -sign * n.x};
  l.t = {b, sign + n.y * n.y * a, -n.y};
  l.n = n;
  l.wo_z = dot(wo, n);
  l.valid = (side != 0) & (l.wo_z != 0) & ~(l.wo_z < 0);
  return l;
}
// The lobe of a LambertianLaneRows batch's lanes first to first + 7.
template <class Batch>
[[gnu::always_inline]] inline Lobe lambertian_lobe(const Batch& batch, int first) {
  using F = LambertianSurfaceFields;
  return lambertian_lobe(rows(batch, F::kNs, first), rows(batch, F::kNg, first), rows(batch, F::kWo, first));
}

// Bsdf::evaluate for the Lambertian lobe alone (f: albedo / pi): consistent(), then f |cos| and the
// cosine density, both zero where wi is below the lobe or the lobe is not valid.
struct LobeValue {
  V8 f_cos;
  F8 pdf;
};
[[gnu::always_inline]] inline LobeValue lambertian_value(const Lobe& lobe, const V8& f, const V8& wi) {
  const F8 z = dot(wi, lobe.n);
  const M8 above = lobe.valid & consistent(wi, z, lobe.ng, lobe.wo_dot_ng, lobe.wo_z) & (z > 0) & (lobe.wo_z > 0);
  return {pick(above, mul(f, absolute(z)), V8{}), pick(above, z * splat(kInvPi), splat(0.0f))};
}

}  // namespace lanes
}  // namespace prism
