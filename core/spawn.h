// Scale-aware ray spawning: offsets origins by the bounded error of the hit point, never a fixed epsilon.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/ray.h"
#include "core/surface_hit.h"
#include "core/vec3.h"

namespace prism {

// Relative error assumed for a recomputed hit point: 32 float ulps (2^-19), four times pbrt's
// gamma(7) bound, because Embree's own intersection test adds error we cannot bound exactly.
inline constexpr float kHitRelativeError = 0x1p-19f;

// Fraction of a shadow segment left unoccupied at its far end (pbrt-v4's ShadowEpsilon): the
// target point is itself offset, so this only absorbs Embree's error in t.
inline constexpr float kShadowEpsilon = 1e-4f;

// The next float above / below v, as std::nextafter toward +inf / -inf, without the libm call:
// adjacent floats of one sign have adjacent bit patterns (IEEE 754 §3.4), so a step away from
// zero adds one to the pattern and a step toward it subtracts one. NaN and +inf stay as they are.
inline float next_float_up(float v) {
  if (std::isnan(v) || v == std::numeric_limits<float>::infinity()) return v;
  if (v == 0.0f) v = 0.0f;  // -0 steps up to the smallest positive denormal, as +0 does
  const uint32_t bits = std::bit_cast<uint32_t>(v);
  return std::bit_cast<float>(v >= 0 ? bits + 1 : bits - 1);
}
inline float next_float_down(float v) { return -next_float_up(-v); }

// Offsets p off its surface (normal n, per-axis error bound err) to the side that w points to,
// then rounds each coordinate away from p so the offset survives float rounding
// (pbrt-v4, "Robust Spawned Ray Origins", Physically Based Rendering 4th ed. §6.8.6).
inline Vec3 offset_ray_origin(const Vec3& p, const Vec3& err, const Vec3& n, const Vec3& w) {
  const float d = dot(abs(n), err);
  Vec3 offset = n * d;
  if (dot(w, n) < 0) offset = -offset;
  Vec3 po = p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0)
      po[i] = next_float_up(po[i]);
    else if (offset[i] < 0)
      po[i] = next_float_down(po[i]);
  }
  return po;
}

// A ray leaving a surface hit in direction dir. origin: offset_ray_origin's for dir, where the
// caller computed it already (the SIMD lanes, integrators/lane_bounce.h).
inline Ray spawn_ray(const SurfaceHit& from, const Vec3& dir, const Vec3* origin = nullptr) {
  return Ray{origin ? *origin : offset_ray_origin(from.p, from.p_error, from.ng, dir), dir, 0.0f,
             std::numeric_limits<float>::infinity(), from.triangle};
}

// spawn_ray(from, dir), whose cone goes on from `from`'s width (SurfaceHit::cone_width) with the
// spread of `arriving`, the ray that found it: as after a mirror, so a rough bounce's footprint is
// underestimated (textures too sharp there, never too blurred). origin: as for spawn_ray.
inline Ray spawn_ray_cone(const SurfaceHit& from, const Vec3& dir, const Ray& arriving, const Vec3* origin = nullptr) {
  Ray r = spawn_ray(from, dir, origin);
  r.cone_width = from.cone_width;
  r.cone_spread = arriving.cone_spread;
  return r;
}

// A shadow ray from a surface hit toward a light `distance` away along unit direction w (+inf
// for lights at infinity), stopping just short of it.
inline Ray spawn_ray_toward(const SurfaceHit& from, const Vec3& w, float distance) {
  Ray r = spawn_ray(from, w);
  r.t_max = std::isinf(distance) ? distance : distance * (1.0f - kShadowEpsilon);
  return r;
}

// A shadow ray from a surface hit to a point on another surface, each offset off its own surface
// toward the other; the direction is unnormalised so t runs from 0 (from) to 1 (to).
inline Ray spawn_ray_between(const SurfaceHit& from, const Vec3& p_to, const Vec3& err_to, const Vec3& n_to) {
  const Vec3 origin = offset_ray_origin(from.p, from.p_error, from.ng, p_to - from.p);
  const Vec3 to = offset_ray_origin(p_to, err_to, n_to, origin - p_to);
  return Ray{origin, to - origin, 0.0f, 1.0f - kShadowEpsilon, from.triangle};
}

}  // namespace prism
