// LaneBounce, lanes::bounce: a Lambertian or coated vertex's bounce drawn in lanes.
#pragma once

#include <iterator>

#include "core/constants.h"
#include "core/sampling.h"
#include "core/vec3.h"
#include "integrators/lane_coated_lobe.h"
#include "integrators/lane_lambertian_lobe.h"
#include "integrators/lane_math.h"

namespace prism {

// What Bsdf::sample gives for the vertex's Lambertian or coated lobes (sampled false where it gives
// nothing), and the origin spawn_ray would give the ray leaving the hit along wi.
struct LaneBounce {
  Vec3 wi, origin;
  Rgb f_cos;
  float pdf = 0;
  bool sampled = false;
};

namespace lanes {

// For lanes first to first + 7 of a batch (LaneVertexBatch) whose lanes ask for it
// (kWantsBounce), bit for bit what Bsdf::sample and spawn_ray make of the bounce: the
// cosine-weighted direction (sample_cosine_hemisphere, through the concentric map), its value and
// density, Bsdf::sample's checks, and the next ray's origin; at coated lanes, the mixture's sample
// (lanes::coated_sample) from the same disk point (kCoated: the block may hold coated lanes).
template <bool kCoated, class B>
[[gnu::always_inline]] inline void bounce(const B& batch, int first, const Lobe& lobe, const Coats& coats,
                                          LaneBounce* out) {
  const int f = first;
  const V8 ng = rows(batch, B::kNg, f), p = rows(batch, B::kP, f), p_error = rows(batch, B::kPError, f);
  const V8 albedo_f = rows(batch, B::kF, f);
  const F8 ux = row(batch, B::kBounceUx, f), uy = row(batch, B::kBounceUy, f);
  // sample_uniform_disk_concentric: the wedge pair u falls in, the angle's sine and cosine.
  const F8 ox = splat(2.0f) * ux - splat(1.0f), oy = splat(2.0f) * uy - splat(1.0f);
  const M8 centre = (ox == 0) & (oy == 0);
  const M8 x_major = absolute(ox) > absolute(oy);
  const F8 r = pick(x_major, ox, oy);
  F8 sine, cosine;
  sin_cos_quarter_of(splat(kPiOver4) * (pick(x_major, oy, ox) / r), sine, cosine);
  const F8 dx = pick(centre, splat(0.0f), pick(x_major, r * cosine, r * sine));
  const F8 dy = pick(centre, splat(0.0f), pick(x_major, r * sine, r * cosine));
  const F8 below = splat(1.0f) - dx * dx - dy * dy;
  const F8 z = root(pick(splat(0.0f) < below, below, splat(0.0f)));
  // Frame::to_world, Lambertian's f |cos| and density, and Bsdf::consistent.
  V8 wi = add(add(mul(lobe.s, dx), mul(lobe.t, dy)), mul(lobe.n, z));
  F8 pdf = pick(z < 0, splat(0.0f), z) * splat(kInvPi);
  V8 f_cos = mul(albedo_f, absolute(z));
  const M8 wants = row(batch, B::kWantsBounce, f) != 0;
  M8 sampled = wants & lobe.valid & (pdf > 0) & consistent(wi, z, lobe.ng, lobe.wo_dot_ng, lobe.wo_z) &
               any_nonzero(f_cos);
  if (kCoated && any(coats.coated & wants)) {
    const CoatedSample c =
        coated_sample(lobe, coats.o, albedo_f, coats.mix, row(batch, B::kBounceULobe, f), dx, dy, V8{dx, dy, z});
    wi = pick(coats.coated, c.wi, wi);
    f_cos = pick(coats.coated, c.f_cos, f_cos);
    pdf = pick(coats.coated, c.pdf, pdf);
    sampled = (coats.coated & wants & c.sampled) | (~coats.coated & sampled);
  }
  // spawn_ray's origin.
  const V8 origin = offset_ray_origin(p, p_error, ng, wi);
  const F8 fields[] = {wi.x, wi.y, wi.z, origin.x, origin.y, origin.z, f_cos.x, f_cos.y, f_cos.z, pdf};
  alignas(32) float o[std::size(fields)][kLanes];
  bool sampled_k[kLanes];
  const int lanes = unpack(fields, sampled, batch.size() - first, o, sampled_k);
  for (int k = 0; k < lanes; ++k) {
    LaneBounce& b = out[first + k];
    b.sampled = sampled_k[k];
    if (!b.sampled) continue;
    b.wi = {o[0][k], o[1][k], o[2][k]};
    b.origin = {o[3][k], o[4][k], o[5][k]};
    b.f_cos = {o[6][k], o[7][k], o[8][k]};
    b.pdf = o[9][k];
  }
}

}  // namespace lanes
}  // namespace prism
