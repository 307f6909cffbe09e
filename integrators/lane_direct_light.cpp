#include "integrators/lane_direct_light.h"

#include <algorithm>
#include <iterator>

#include "core/constants.h"
#include "integrators/lane_math.h"

namespace prism {
namespace {

using namespace lanes;

// Lanes first to first + 7 of the batch: the lobe's frame, the light sample, the lobe's value, the
// shadow ray and the contribution.
[[gnu::always_inline]] inline void eight_lanes(const LaneLightBatch& batch, int first, LaneLightResult* out) {
  using B = LaneLightBatch;
  const int f = first;
  const struct {
    V8 p, p_error, ng, f, beta, c0, c1, c2, light_n, emission;
    F8 b0, b1, b2, quad_slack, pdf_area, pmf, double_sided;
  } l{rows(batch, B::kP, f),      rows(batch, B::kPError, f), rows(batch, B::kNg, f),      rows(batch, B::kF, f),
      rows(batch, B::kBeta, f),   rows(batch, B::kC0, f),     rows(batch, B::kC1, f),      rows(batch, B::kC2, f),
      rows(batch, B::kLightN, f), rows(batch, B::kEmission, f), row(batch, B::kB0, f),     row(batch, B::kB1, f),
      row(batch, B::kB2, f),      row(batch, B::kSlack, f),   row(batch, B::kPdfArea, f),  row(batch, B::kPmf, f),
      row(batch, B::kDoubleSided, f)};
  const Lobe lobe = lambertian_lobe(batch, f);
  // Emitters::triangle_point and area_to_solid_angle, then the light's pick probability.
  const V8 w0 = mul(l.c0, l.b0), w1 = mul(l.c1, l.b1), w2 = mul(l.c2, l.b2);
  const V8 lp = add(add(w0, w1), w2);
  const F8 rel = splat(kHitRelativeError);
  const V8 slack{l.quad_slack, l.quad_slack, l.quad_slack};
  const V8 lp_error = add(mul(add(add(absolute(w0), absolute(w1)), absolute(w2)), rel), slack);
  const V8 to_light = sub(lp, l.p);
  const F8 dist2 = dot(to_light, to_light);
  const F8 dist = root(dist2);
  const F8 cos_p = absolute(dot(l.light_n, to_light)) / dist;
  const F8 pdf = pick(cos_p > 0, l.pdf_area * dist2 / cos_p, splat(0.0f)) * l.pmf;
  // direct_light: the direction, the radiance leaving the light toward the vertex.
  const V8 wi = mul(to_light, splat(1.0f) / dist);
  const V8 back{-wi.x, -wi.y, -wi.z};
  const M8 emits = (l.double_sided != 0) | ~(dot(l.light_n, back) <= 0);
  const V8 incident = pick(emits, l.emission, V8{});
  // Bsdf::evaluate for the Lambertian lobe alone: consistent(), then f |cos| and the cosine density.
  const F8 z = dot(wi, lobe.n);
  const M8 above = lobe.valid & consistent(wi, z, lobe.ng, lobe.wo_dot_ng, lobe.wo_z) & (z > 0) & (lobe.wo_z > 0);
  const V8 f_cos = pick(above, mul(l.f, absolute(z)), V8{});
  const F8 bsdf_pdf = pick(above, z * splat(kInvPi), splat(0.0f));
  const M8 cast = (pdf > 0) & any_nonzero(incident) & any_nonzero(f_cos);
  // spawn_ray_between: each end offset off its own surface toward the other.
  const V8 origin = offset_ray_origin(l.p, l.p_error, l.ng, to_light);
  const V8 to = offset_ray_origin(lp, lp_error, l.light_n, sub(origin, lp));
  const V8 dir = sub(to, origin);
  // power_heuristic(pdf, bsdf_pdf), and the contribution with beta (beer_lambert is 1 here).
  const F8 a = pdf * pdf, b = bsdf_pdf * bsdf_pdf;
  const F8 sum = a + b;
  const F8 weight = pick(a == splat(std::numeric_limits<float>::infinity()), splat(1.0f),
                         pick(sum > 0, a / sum, splat(0.0f)));
  const V8 contribution = mul(l.beta, mul(mul(f_cos, incident), weight / pdf));
  const F8 fields[] = {origin.x, origin.y, origin.z,       dir.x,         dir.y,
                       dir.z,    contribution.x, contribution.y, contribution.z};
  alignas(32) float o[std::size(fields)][kLanes];
  alignas(32) int32_t c[kLanes];
  for (size_t i = 0; i < std::size(fields); ++i) std::memcpy(o[i], &fields[i], sizeof(F8));
  std::memcpy(c, &cast, sizeof(M8));
  for (int k = 0; k < std::min(kLanes, batch.size() - first); ++k) {
    LaneLightResult& r = out[first + k];
    r.cast = c[k] != 0;
    if (!r.cast) continue;
    r.ray = Ray{{o[0][k], o[1][k], o[2][k]}, {o[3][k], o[4][k], o[5][k]}, 0.0f, 1.0f - kShadowEpsilon,
                batch.leaves(first + k)};
    r.contribution = {o[6][k], o[7][k], o[8][k]};
  }
}

}  // namespace

int LaneLightBatch::add(const LambertianSurface& surface, const Vec3& p, const Vec3& p_error, TriangleId leaves,
                        const Rgb& beta, const Emitters::AreaDraw& light, const Rgb& emission, bool double_sided) {
  const int lane = add_surface(surface, p, p_error);
  leaves_[lane] = leaves;
  set(kBeta, lane, beta);
  set(kC0, lane, light.c0());
  set(kC1, lane, light.c1());
  set(kC2, lane, light.c2());
  set(kB0, lane, light.b.b0);
  set(kB1, lane, light.b.b1);
  set(kB2, lane, light.b.b2);
  set(kLightN, lane, light.light->normal);
  set(kSlack, lane, light.light->quad_slack);
  set(kPdfArea, lane, 1.0f / light.light->area);
  set(kPmf, lane, light.pmf);
  set(kEmission, lane, emission);
  set(kDoubleSided, lane, double_sided ? 1.0f : 0.0f);
  return lane;
}

void lane_direct_light(const LaneLightBatch& batch, LaneLightResult* out, bool avx2) {
  run_lanes<eight_lanes>(batch, out, avx2);
}

}  // namespace prism
