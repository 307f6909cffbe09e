// lanes: eight-lane arithmetic for the path tracer's SIMD kernels, each operation rounding as its scalar form does.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include "core/arctangent.h"
#include "core/cpu_features.h"
#include "core/float8.h"
#include "core/spawn.h"

namespace prism::lanes {

// A kernel built from these makes the scalar code's operations in the same order (IEEE adds,
// multiplies, divides and square roots; no fused multiply-adds, no reassociation), so that lane k
// holds the bits the scalar code computes for request k. Every function is always inlined: compiled
// into a target("avx2") kernel they are AVX instructions, and no call passes an eight-lane vector.
using F8 = Float8Lanes;
using M8 = Mask8Lanes;
constexpr int kLanes = 8;  // lanes taken at once

struct V8 {
  F8 x, y, z;
};

[[gnu::always_inline]] inline F8 splat(float v) { return F8{} + v; }
[[gnu::always_inline]] inline V8 add(const V8& a, const V8& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
[[gnu::always_inline]] inline V8 sub(const V8& a, const V8& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
[[gnu::always_inline]] inline V8 mul(const V8& a, F8 s) { return {a.x * s, a.y * s, a.z * s}; }
[[gnu::always_inline]] inline V8 mul(const V8& a, const V8& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
[[gnu::always_inline]] inline F8 dot(const V8& a, const V8& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
[[gnu::always_inline]] inline F8 absolute(F8 a) { return vabs(Float8(a)).v; }
[[gnu::always_inline]] inline V8 absolute(const V8& a) { return {absolute(a.x), absolute(a.y), absolute(a.z)}; }
[[gnu::always_inline]] inline F8 root(F8 a) { return vsqrt(Float8(a)).v; }
[[gnu::always_inline]] inline F8 pick(M8 m, F8 a, F8 b) { return select(Mask8{m}, Float8(a), Float8(b)).v; }
[[gnu::always_inline]] inline V8 pick(M8 m, const V8& a, const V8& b) {
  return {pick(m, a.x, b.x), pick(m, a.y, b.y), pick(m, a.z, b.z)};
}
[[gnu::always_inline]] inline M8 any_nonzero(const V8& a) { return (a.x != 0) | (a.y != 0) | (a.z != 0); }
// Whether any lane of m is set.
[[gnu::always_inline]] inline bool any(M8 m) {
  int32_t lanes[8];
  std::memcpy(lanes, &m, sizeof m);
  int32_t set = 0;
  for (const int32_t lane : lanes) set |= lane;
  return set != 0;
}
[[gnu::always_inline]] inline V8 cross(const V8& a, const V8& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// std::min and std::max: the first argument where neither is less (a NaN b gives a).
[[gnu::always_inline]] inline F8 minimum(F8 a, F8 b) { return pick(b < a, b, a); }
[[gnu::always_inline]] inline F8 maximum(F8 a, F8 b) { return pick(a < b, b, a); }
// The bits of `magnitude` with the sign of `sign` (std::copysign).
[[gnu::always_inline]] inline F8 copy_sign(F8 magnitude, F8 sign) {
  constexpr int32_t kSignBit = std::numeric_limits<int32_t>::min();
  return reinterpret_cast<F8>((reinterpret_cast<M8>(magnitude) & ~kSignBit) | (reinterpret_cast<M8>(sign) & kSignBit));
}

// atan2_fast (core/arctangent.h) lane by lane, its branches as selects.
[[gnu::always_inline]] inline F8 atan2_fast(F8 y, F8 x) {
  using namespace atan2_parts;
  const F8 ax = absolute(x), ay = absolute(y);
  const F8 hi = maximum(ax, ay), lo = minimum(ax, ay);
  F8 a = pick(hi > 0, lo / hi, splat(0.0f));
  a = pick(a != a, splat(1.0f), a);  // both infinite
  const M8 reduced = a > kTanPiOver8;
  F8 r = atan_reduced(pick(reduced, (a - 1.0f) / (a + 1.0f), a));
  r = pick(reduced, kPi / 4 + (r + kQuarterPiLow), r);
  r = pick(ay > ax, kPi / 2 - (r - kHalfPiLow), r);
  const M8 negative_zero = (x == 0) & (reinterpret_cast<M8>(x) < 0);
  r = pick((x < 0) | negative_zero, kPi - (r - kPiLow), r);
  return pick((x != x) | (y != y), x + y, copy_sign(r, y));
}

// next_float_up (core/spawn.h) lane by lane: NaN and +inf stay, -0 steps as +0 does, and the bit
// pattern steps away from zero for positive values, toward it for negative ones.
[[gnu::always_inline]] inline F8 float_up(F8 v) {
  const M8 keep = (v != v) | (v == splat(std::numeric_limits<float>::infinity()));
  const F8 from = pick(v == 0, splat(0.0f), v);
  const M8 step = ((from >= 0) & 2) - 1;  // +1 or -1
  return pick(keep, v, reinterpret_cast<F8>(reinterpret_cast<M8>(from) + step));
}
// next_float_down(v) = -next_float_up(-v).
[[gnu::always_inline]] inline F8 float_down(F8 v) { return -float_up(-v); }

// One coordinate c of an offset origin rounded away from the surface, the way its offset o points.
[[gnu::always_inline]] inline F8 step_away(F8 o, F8 c) {
  return pick(o > 0, float_up(c), pick(o < 0, float_down(c), c));
}

// offset_ray_origin (core/spawn.h).
[[gnu::always_inline]] inline V8 offset_ray_origin(const V8& p, const V8& err, const V8& n, const V8& w) {
  const F8 d = dot(absolute(n), err);
  V8 offset = mul(n, d);
  const M8 flip = dot(w, n) < 0;
  offset = pick(flip, V8{-offset.x, -offset.y, -offset.z}, offset);
  const V8 po = add(p, offset);
  return {step_away(offset.x, po.x), step_away(offset.y, po.y), step_away(offset.z, po.z)};
}

// Bsdf::consistent lane by lane: shading and geometric normals agree on wi's side. z: wi's cosine
// about the shading normal; ng, wo_dot_ng, wo_z: the BSDF's (lanes::Lobe).
[[gnu::always_inline]] inline M8 consistent(const V8& wi, F8 z, const V8& ng, F8 wo_dot_ng, F8 wo_z) {
  const F8 geometric = dot(wi, ng) * wo_dot_ng;
  const F8 shading = z * wo_z;
  return (geometric != 0) & (shading != 0) & ((geometric > 0) == (shading > 0));
}

// A kernel's results, lane by lane: lane k of fields[i] into o[i][k] and of `mask` into set[k], for
// the first `count` lanes (at most kLanes, the lanes in use). Returns how many.
template <size_t N>
[[gnu::always_inline]] inline int unpack(const F8 (&fields)[N], M8 mask, int count, float (&o)[N][kLanes],
                                         bool (&set)[kLanes]) {
  alignas(32) int32_t m[kLanes];
  for (size_t i = 0; i < N; ++i) std::memcpy(o[i], &fields[i], sizeof(F8));
  std::memcpy(m, &mask, sizeof(M8));
  const int lanes = count < kLanes ? count : kLanes;
  for (int k = 0; k < lanes; ++k) set[k] = m[k] != 0;
  return lanes;
}

// Lanes first to first + 7 of a row of floats.
[[gnu::always_inline]] inline F8 load(const float* row, int first) { return load8(row + first).v; }
// And back: eight lanes into out[0..7].
[[gnu::always_inline]] inline void store(F8 v, float* out) { store8(out, Float8(v)); }
// Of a batch's row r (LaneRows), and of rows r to r + 2 as vectors.
template <class Batch>
[[gnu::always_inline]] inline F8 row(const Batch& b, int r, int first) {
  return load(b.row(r), first);
}
template <class Batch>
[[gnu::always_inline]] inline V8 rows(const Batch& b, int r, int first) {
  return {row(b, r, first), row(b, r + 1, first), row(b, r + 2, first)};
}

// kernel(batch, first, out) for first = 0, 8, 16, ... below batch.size(): flattened into an AVX2
// function where the CPU has AVX2 and `avx2` allows it, else into one of SSE pairs (the same bits).
template <auto kernel, class Batch, class Out>
__attribute__((target("avx2"), flatten)) void all_lanes_avx2(const Batch& batch, Out* out) {
  for (int first = 0; first < batch.size(); first += kLanes) kernel(batch, first, out);
}
template <auto kernel, class Batch, class Out>
[[gnu::flatten]] void all_lanes_sse(const Batch& batch, Out* out) {
  for (int first = 0; first < batch.size(); first += kLanes) kernel(batch, first, out);
}
template <auto kernel, class Batch, class Out>
void run_lanes(const Batch& batch, Out* out, bool avx2) {
  if (batch.size() == 0) return;
  if (avx2 && cpu_has_avx2())
    all_lanes_avx2<kernel>(batch, out);
  else
    all_lanes_sse<kernel>(batch, out);
}

}  // namespace prism::lanes
