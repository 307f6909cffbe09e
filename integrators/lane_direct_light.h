// LaneLightResult, lanes::direct_light: next-event estimation at Lambertian and coated vertices, in lanes.
#pragma once

#include <cstring>
#include <iterator>
#include <limits>

#include "core/constants.h"
#include "core/emitters.h"
#include "core/ray.h"
#include "integrators/lane_coated_lobe.h"
#include "integrators/lane_lambertian_lobe.h"
#include "integrators/lane_math.h"
#include "integrators/lane_spherical_triangle.h"

namespace prism {

// The shadow ray to trace and what it adds when unoccluded (beta included); cast false: none.
// Where the lane was to be weighed later (LaneVertexBatch::weigh_later), `contribution` is the
// lobe's value times the incident light alone, and the direction, the light's density and the
// lobe's are given for the caller's MIS weight.
struct LaneLightResult {
  Ray ray;
  Rgb contribution;
  bool cast = false;
  Vec3 wi;
  float pdf = 0, bsdf_pdf = 0;
};

namespace lanes {

// power_heuristic (core/sampling.h).
[[gnu::always_inline]] inline F8 power_heuristic(F8 pdf_a, F8 pdf_b) {
  const F8 a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  const F8 sum = a + b;
  return pick(a == splat(std::numeric_limits<float>::infinity()), splat(1.0f), pick(sum > 0, a / sum, splat(0.0f)));
}

// Where lanes first to first + 7 that cast a shadow ray are to be weighed later (`later`,
// LaneVertexFields::kWeighLater), their results' MIS pieces: the direction and the two densities.
[[gnu::always_inline]] inline void weigh_later(M8 later, const V8& wi, F8 pdf, F8 bsdf_pdf, int count, int first,
                                               LaneLightResult* out) {
  if (!any(later)) return;
  const F8 fields[] = {wi.x, wi.y, wi.z, pdf, bsdf_pdf};
  alignas(32) float o[std::size(fields)][kLanes];
  bool later_k[kLanes];
  const int lanes = unpack(fields, later, count, o, later_k);
  for (int k = 0; k < lanes; ++k) {
    if (!later_k[k]) continue;
    LaneLightResult& r = out[first + k];
    r.wi = {o[0][k], o[1][k], o[2][k]};
    r.pdf = o[3][k];
    r.bsdf_pdf = o[4][k];
  }
}

// For lanes first to first + 7 of a batch (LaneVertexBatch) whose lanes ask for it (kWantsLight),
// what PathIntegrator::direct_light gives, bit for bit: the light sample's point, error bound and
// density (Emitters::sample_light: by solid angle near the light where that pays, else by area),
// the emitted radiance, the surface's value and density (Bsdf::evaluate, of the Lambertian lobe or
// the coated mixture), the shadow ray (spawn_ray_between) and the power-heuristic weight. Outside
// every volume only: no medium absorbs. kCoated: the block may hold coated lanes.
template <bool kCoated, class B>
[[gnu::always_inline]] inline void direct_light(const B& batch, int first, const Lobe& lobe, const Coats& coats,
                                               LaneLightResult* out) {
  const int f = first;
  // The lights' constants, from their records (Emitters::LaneRecord).
  using R = Emitters::LaneRecord;
  F8 c[3][8];
  for (int i = 0; i < 3; ++i) transpose(batch.records(f), 8 * i, c[i]);
  const auto field = [&](int r) { return c[r / 8][r % 8]; };
  const auto vector = [&](int r) { return V8{field(r), field(r + 1), field(r + 2)}; };
  const struct {
    V8 p, p_error, f, beta, p0, p1, p2, p3, light_n, emission;
    F8 ux, uy, quad, quad_slack, pdf_area, pmf, double_sided, longest_edge2, wants;
  } l{rows(batch, B::kP, f),       rows(batch, B::kPError, f),   rows(batch, B::kF, f),      rows(batch, B::kBeta, f),
      vector(R::kP0),              vector(R::kP1),               vector(R::kP2),             vector(R::kP3),
      vector(R::kNormal),          vector(R::kEmission),         row(batch, B::kLightUx, f), row(batch, B::kLightUy, f),
      field(R::kQuad),             field(R::kSlack),             field(R::kPdfArea),         row(batch, B::kPmf, f),
      field(R::kDoubleSided),      field(R::kLongestEdge2),      row(batch, B::kWantsLight, f)};
  // Emitters::triangle_draw's part that depends on the vertex: the light's side it is on (faces),
  // whether it is near (near_enough), and the point by area (area_point_draw: for a triangle
  // sample_uniform_triangle, for a quad the half u falls in).
  const F8 plane_distance = dot(sub(l.p, l.p0), l.light_n);
  const M8 wants = (l.wants == B::kOnTriangle) & ((l.double_sided != 0) | (plane_distance > 0));
  const M8 quad = l.quad != 0;
  const F8 su = root(l.ux);
  const F8 t0 = splat(1.0f) - su, t1 = l.uy * su;
  const M8 lower = l.ux + l.uy <= 1;
  const F8 b0 = pick(quad, pick(lower, splat(1.0f) - l.ux - l.uy, splat(1.0f) - l.uy), t0);
  const F8 b1 = pick(quad, pick(lower, l.ux, l.ux + l.uy - splat(1.0f)), t1);
  const F8 b2 = pick(quad, pick(lower, l.uy, splat(1.0f) - l.ux), splat(1.0f) - t0 - t1);
  const M8 half_by_area = quad & ~lower;
  // Emitters::sample_triangle: by solid angle where the vertex is near the light and that pays
  // (SolidAngleView), u.x choosing a quad's half in proportion to its share and rescaled within it.
  M8 by_solid_angle = wants & (l.longest_edge2 > plane_distance * plane_distance), in_b{};
  F8 solid_angle = splat(0.0f);
  Barycentrics8 at{b0, b1, b2, ~M8{}};  // by area, every lane drawn
  if (any(by_solid_angle)) {
    const Corner8 c0 = see(l.p, l.p0), c1 = see(l.p, l.p1), c2 = see(l.p, l.p2);
    const SphericalTriangle8 a = spherical_triangle(l.p, c0, c1, c2);
    const SphericalTriangle8 b = spherical_triangle(l.p, c1, see(l.p, l.p3), c2);
    solid_angle = a.solid_angle + pick(quad, b.solid_angle, splat(0.0f));
    by_solid_angle &= (solid_angle >= Emitters::kMinSolidAngle) & (solid_angle <= Emitters::kMaxSolidAngle);
    const F8 share_a = a.solid_angle / solid_angle;
    in_b = quad & (l.ux >= share_a);
    const F8 ux = pick(quad, minimum(pick(in_b, (l.ux - share_a) / (splat(1.0f) - share_a), l.ux / share_a),
                                     splat(kOneMinusEpsilon)),
                       l.ux);
    const Barycentrics8 s = sample(pick(in_b, b, a), ux, l.uy);
    at = {pick(by_solid_angle, s.b0, b0), pick(by_solid_angle, s.b1, b1), pick(by_solid_angle, s.b2, b2),
          ~by_solid_angle | s.drawn};
  }
  // Emitters::triangle_point at those barycentrics of the half they are in.
  const M8 half_b = pick(by_solid_angle, in_b, half_by_area);
  const V8 c0 = pick(half_b, l.p1, l.p0), c1 = pick(half_b, l.p3, l.p1), c2 = l.p2;
  const V8 w0 = mul(c0, at.b0), w1 = mul(c1, at.b1), w2 = mul(c2, at.b2);
  const V8 lp = add(add(w0, w1), w2);
  const F8 rel = splat(kHitRelativeError);
  const V8 slack{l.quad_slack, l.quad_slack, l.quad_slack};
  const V8 lp_error = add(mul(add(add(absolute(w0), absolute(w1)), absolute(w2)), rel), slack);
  const V8 to_light = sub(lp, l.p);
  const F8 dist2 = dot(to_light, to_light);
  const F8 dist = root(dist2);
  const F8 cos_p = absolute(dot(l.light_n, to_light)) / dist;
  // The density: 1 / solid angle, or area_to_solid_angle's; then the light's pick probability.
  const F8 pdf =
      pick(by_solid_angle, splat(1.0f) / solid_angle, pick(cos_p > 0, l.pdf_area * dist2 / cos_p, splat(0.0f))) * l.pmf;
  // direct_light: the direction, the radiance leaving the light toward the vertex.
  const V8 wi = mul(to_light, splat(1.0f) / dist);
  const V8 back{-wi.x, -wi.y, -wi.z};
  const M8 emits = (l.double_sided != 0) | ~(dot(l.light_n, back) <= 0);
  const V8 incident = pick(emits, l.emission, V8{});
  const auto [f_cos, bsdf_pdf] = surface_value<kCoated>(lobe, coats, l.f, wi);
  const M8 cast = wants & at.drawn & (pdf > 0) & any_nonzero(incident) & any_nonzero(f_cos);
  // spawn_ray_between: each end offset off its own surface toward the other.
  const V8 origin = offset_ray_origin(l.p, l.p_error, rows(batch, B::kNg, f), to_light);
  const V8 to = offset_ray_origin(lp, lp_error, l.light_n, sub(origin, lp));
  const V8 dir = sub(to, origin);
  // The contribution with beta (beer_lambert is 1 here), or its unweighted part.
  const V8 unweighted = mul(f_cos, incident);
  const M8 later = row(batch, B::kWeighLater, f) != 0;
  const V8 contribution =
      pick(later, unweighted, mul(l.beta, mul(unweighted, power_heuristic(pdf, bsdf_pdf) / pdf)));
  const F8 fields[] = {origin.x, origin.y, origin.z, dir.x, dir.y, dir.z, contribution.x, contribution.y, contribution.z};
  alignas(32) float o[std::size(fields)][kLanes];
  bool cast_k[kLanes];
  const int lanes = unpack(fields, cast, batch.size() - first, o, cast_k);
  for (int k = 0; k < lanes; ++k) {
    LaneLightResult& r = out[first + k];
    r.cast = cast_k[k];
    if (!r.cast) continue;
    r.ray = Ray{{o[0][k], o[1][k], o[2][k]}, {o[3][k], o[4][k], o[5][k]}, 0.0f, 1.0f - kShadowEpsilon,
                batch.leaves(first + k)};
    r.contribution = {o[6][k], o[7][k], o[8][k]};
  }
  weigh_later(later & cast, wi, pdf, bsdf_pdf, batch.size() - first, first, out);
}

// direct_light's case of a light with no point to reach, for the lanes that ask for it (kToward):
// a punctual light or the sky, whose sample (Emitters::sample_light) is a direction, a distance (+inf
// for the sky and the sun), the incident radiance (or irradiance) and a density. What
// PathIntegrator::direct_light gives, bit for bit: the lobe's value, the shadow ray
// (spawn_ray_toward) and the weight, 1 for a punctual light (no MIS), else the power heuristic.
// It writes the results of those lanes only.
template <bool kCoated, class B>
[[gnu::always_inline]] inline void direct_light_toward(const B& batch, int first, const Lobe& lobe,
                                                       const Coats& coats, LaneLightResult* out) {
  const int f = first;
  const V8 wi = rows(batch, B::kTowardW, f), incident = rows(batch, B::kIncident, f);
  const F8 distance = row(batch, B::kTowardDistance, f), pdf = row(batch, B::kTowardPdf, f);
  const M8 wants = row(batch, B::kWantsLight, f) == B::kToward;
  const auto [f_cos, bsdf_pdf] = surface_value<kCoated>(lobe, coats, rows(batch, B::kF, f), wi);
  const M8 cast = wants & any_nonzero(incident) & any_nonzero(f_cos);
  const V8 origin = offset_ray_origin(rows(batch, B::kP, f), rows(batch, B::kPError, f), rows(batch, B::kNg, f), wi);
  const F8 infinity = splat(std::numeric_limits<float>::infinity());
  const F8 t_max = pick(absolute(distance) == infinity, distance, distance * (1.0f - kShadowEpsilon));
  const F8 weight = pick(row(batch, B::kTowardDelta, f) != 0, splat(1.0f), power_heuristic(pdf, bsdf_pdf));
  const V8 unweighted = mul(f_cos, incident);
  const M8 later = wants & (row(batch, B::kWeighLater, f) != 0);
  const V8 contribution = pick(later, unweighted, mul(rows(batch, B::kBeta, f), mul(unweighted, weight / pdf)));
  const F8 fields[] = {origin.x, origin.y, origin.z, t_max, contribution.x, contribution.y, contribution.z};
  alignas(32) float o[std::size(fields)][kLanes];
  bool cast_k[kLanes];
  const int lanes = unpack(fields, cast, batch.size() - first, o, cast_k);
  alignas(32) int32_t wants_k[kLanes];
  std::memcpy(wants_k, &wants, sizeof wants);
  for (int k = 0; k < lanes; ++k) {
    if (!wants_k[k]) continue;
    LaneLightResult& r = out[first + k];
    r.cast = cast_k[k];
    if (!r.cast) continue;
    const Vec3 w{batch.row(B::kTowardW)[first + k], batch.row(B::kTowardW + 1)[first + k],
                 batch.row(B::kTowardW + 2)[first + k]};
    r.ray = Ray{{o[0][k], o[1][k], o[2][k]}, w, 0.0f, o[3][k], batch.leaves(first + k)};
    r.contribution = {o[4][k], o[5][k], o[6][k]};
  }
  weigh_later(later & cast, wi, pdf, bsdf_pdf, batch.size() - first, first, out);
}

}  // namespace lanes
}  // namespace prism
