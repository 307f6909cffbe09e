// lanes::coated_*: glTF's opaque metallic-roughness BSDF (GGX metal; a GGX layer over a Lambertian lobe) in lanes.
#pragma once

#include <algorithm>

#include "core/constants.h"
#include "integrators/lane_lambertian_lobe.h"
#include "integrators/lane_math.h"
#include "materials/surface_params.h"

namespace prism {

// A vertex whose Bsdf is glTF's opaque metallic-roughness mixture with rough lobes (Bsdf::coated_only),
// beyond its LambertianSurface: the lobes' GGX alpha (roughness^2), the layer's relative index, the
// metallic weight, the base colour (the metal's F0), and the diffuse lobe's albedo estimate for the
// lobe pick, max(luminance(base colour), 0.05).
struct CoatedSurface {
  float alpha = 0, eta = 1, metallic = 0;
  Rgb base_color;
  float diffuse_albedo = 0;

  // Bsdf::Bsdf's constants for the lobes and the diffuse lobe's pick, for a surface of `params`
  // at relative index eta.
  static CoatedSurface of(const SurfaceParams& params, float eta) {
    return {params.roughness * params.roughness, eta, std::clamp(params.metallic, 0.0f, 1.0f), params.base_color,
            std::max(luminance(params.base_color), 0.05f)};
  }
};

namespace lanes {

// What Bsdf's constructor makes of the mixture at wo: the metal has weight m, the layer 1 - m and
// reflects F(wo), the diffuse lobe (1 - m)(1 - F(wo)); each is picked in proportion to its albedo
// estimate. valid: the Bsdf's valid_.
struct CoatedMixture {
  F8 alpha, eta, metallic;
  V8 f0;
  F8 coat_weight, diffuse_weight, metal_pick, coat_pick, diffuse_pick;
  M8 valid;
};

// fresnel_dielectric for cos_i >= 0 (or -0): 1 past the critical angle.
[[gnu::always_inline]] inline F8 fresnel_dielectric_front(F8 cos_i, F8 eta) {
  const F8 c = pick(splat(1.0f) < cos_i, splat(1.0f), cos_i);  // std::clamp's upper bound
  const F8 eta2_cos2_t = (eta - splat(1.0f)) * (eta + splat(1.0f)) + c * c;
  const F8 eta_cos_t = root(maximum(eta2_cos2_t, splat(0.0f)));
  const F8 eta2_cos_i = eta * eta * c;
  const F8 r_s = (c - eta_cos_t) / (c + eta_cos_t);
  const F8 r_p = (eta2_cos_i - eta_cos_t) / (eta2_cos_i + eta_cos_t);
  return pick(eta2_cos2_t <= 0, splat(1.0f), splat(0.5f) * (r_s * r_s + r_p * r_p));
}

// fresnel_schlick: F0 + (1 - F0)(1 - |cos|)^5, per channel.
[[gnu::always_inline]] inline V8 fresnel_schlick(const V8& f0, F8 cos_i) {
  const F8 x = splat(1.0f) - absolute(cos_i);
  const F8 m = pick(x < 0, splat(0.0f), pick(splat(1.0f) < x, splat(1.0f), x));  // std::clamp(x, 0, 1)
  const F8 m5 = (m * m) * (m * m) * m;
  return {f0.x + (splat(1.0f) - f0.x) * m5, f0.y + (splat(1.0f) - f0.y) * m5, f0.z + (splat(1.0f) - f0.z) * m5};
}

[[gnu::always_inline]] inline F8 luminance(const V8& c) {
  return splat(0.2126f) * c.x + splat(0.7152f) * c.y + splat(0.0722f) * c.z;
}

// The mixture's weights and picks (Bsdf::Bsdf, in its order) for lanes whose wo is above the lobe.
[[gnu::always_inline]] inline CoatedMixture coated_mixture(const Lobe& lobe, F8 alpha, F8 eta, F8 metallic,
                                                           const V8& f0, F8 diffuse_albedo) {
  CoatedMixture mix;
  mix.alpha = alpha;
  mix.eta = eta;
  mix.metallic = metallic;
  mix.f0 = f0;
  const F8 r = pick(metallic < 1, fresnel_dielectric_front(lobe.wo_z, eta), splat(0.0f));
  mix.coat_weight = splat(1.0f) - metallic;  // (1 - m)(1 - t), t = 0
  mix.diffuse_weight = mix.coat_weight * maximum(splat(0.0f), splat(1.0f) - r);
  const F8 metal = pick(metallic > 0, metallic * maximum(luminance(fresnel_schlick(f0, lobe.wo_z)), splat(0.05f)),
                        splat(0.0f));
  const F8 coat = mix.coat_weight * luminance(V8{r, r, r});
  const F8 diffuse = mix.diffuse_weight * diffuse_albedo;
  const F8 total = metal + coat + diffuse;  // ((metal + 0) + coat) + diffuse: the dielectric's pick is 0
  mix.valid = lobe.valid & (total > 0);
  mix.metal_pick = pick(mix.valid, metal / total, splat(0.0f));
  mix.coat_pick = pick(mix.valid, coat / total, splat(0.0f));
  mix.diffuse_pick = pick(mix.valid, diffuse / total, splat(0.0f));
  return mix;
}

// GgxDistribution::lambda.
[[gnu::always_inline]] inline F8 ggx_lambda(const V8& w, F8 alpha) {
  const F8 c2 = w.z * w.z;
  const F8 tan2 = (w.x * w.x + w.y * w.y) / c2;
  return pick(c2 <= 0, splat(1e30f), splat(0.5f) * (root(splat(1.0f) + alpha * alpha * tan2) - splat(1.0f)));
}

// The glossy lobes at local o and i, from what they share (the half vector, D, G, the visible
// normals' density): the layer's DielectricBxdf::evaluate (ReflectionOnly, its exact Fresnel curve;
// f the same in every channel) and the metal's ConductorBxdf::evaluate (Schlick's Fresnel from F0);
// each zero where it reflects nothing.
struct GlossyValues {
  F8 coat_f, coat_pdf;
  V8 metal_f;
  F8 metal_pdf;
};
[[gnu::always_inline]] inline GlossyValues glossy_values(const V8& o, const V8& i, const CoatedMixture& mix) {
  const F8 alpha = mix.alpha;
  const V8 h = add(o, i);
  const F8 len2 = dot(h, h);
  const V8 unit = mul(h, splat(1.0f) / root(len2));
  const V8 wm = pick(unit.z < 0, negate(unit), unit);  // the layer's turns to +z; the metal's is there already
  const F8 wm_o = dot(wm, o);
  const M8 coat = (o.z * i.z > 0) & (len2 > 0) & ~(dot(wm, i) * i.z < 0) & ~(wm_o * o.z < 0);
  const M8 metal = ~(o.z <= 0) & ~(i.z <= 0) & (len2 > 0);
  // D (Walter et al. 2007, eq. 33), height-correlated G, and the visible normals' density.
  const F8 a2 = alpha * alpha;
  const F8 c2 = wm.z * wm.z;
  const F8 t = (wm.x * wm.x + wm.y * wm.y) + c2 * a2;
  const F8 d = pick(c2 <= 0, splat(0.0f), a2 / (splat(kPi) * t * t));
  const F8 lambda_o = ggx_lambda(o, alpha), lambda_i = ggx_lambda(i, alpha);
  const F8 g = splat(1.0f) / (splat(1.0f) + lambda_o + lambda_i);
  const F8 cos_o = absolute(o.z), cos_i = absolute(i.z);
  const F8 visible = splat(1.0f) / (splat(1.0f) + lambda_o) * maximum(splat(0.0f), absolute(wm_o)) * d / cos_o;
  const F8 pdf = visible / (splat(4.0f) * absolute(wm_o));
  GlossyValues v;
  v.coat_f = pick(coat, fresnel_dielectric_front(wm_o, mix.eta) * (d * g / (splat(4.0f) * cos_i * cos_o)), splat(0.0f));
  v.coat_pdf = pick(coat, pdf, splat(0.0f));
  v.metal_f = pick(metal, mul(fresnel_schlick(mix.f0, wm_o), d * g / (splat(4.0f) * o.z * i.z)), V8{});
  v.metal_pdf = pick(metal, pdf, splat(0.0f));
  return v;
}

// Bsdf::evaluate of the mixture, in its order: wi into the frame, consistent(), then each lobe with
// weight (metal, layer, diffuse) adds its value times its weight, and each lobe with a pick its
// density times its pick. o, i: wo and wi in the lobes' frame; f: albedo / pi.
[[gnu::always_inline]] inline LobeValue mixture_value(const V8& o, const V8& i, const V8& f, const CoatedMixture& mix) {
  const GlossyValues glossy = glossy_values(o, i, mix);
  const M8 diffuse = (i.z > 0) & (o.z > 0);
  const V8 diffuse_f = pick(diffuse, f, V8{});
  const F8 diffuse_pdf = pick(diffuse, i.z * splat(kInvPi), splat(0.0f));
  const F8 coat_f = glossy.coat_f * mix.coat_weight;
  const V8 sum = add(add(pick(mix.metallic > 0, mul(glossy.metal_f, mix.metallic), V8{}),
                         pick(mix.coat_weight > 0, V8{coat_f, coat_f, coat_f}, V8{})),
                     pick(mix.diffuse_weight > 0, mul(diffuse_f, mix.diffuse_weight), V8{}));
  const F8 pdf = pick(mix.metal_pick > 0, mix.metal_pick * glossy.metal_pdf, splat(0.0f)) +
                 pick(mix.coat_pick > 0, mix.coat_pick * glossy.coat_pdf, splat(0.0f)) +
                 pick(mix.diffuse_pick > 0, mix.diffuse_pick * diffuse_pdf, splat(0.0f));
  return {mul(sum, absolute(i.z)), pdf};
}

// wo in the lobes' frame (Bsdf's wo_), from world wo.
[[gnu::always_inline]] inline V8 local_wo(const Lobe& lobe, const V8& wo) {
  return {dot(wo, lobe.s), dot(wo, lobe.t), lobe.wo_z};
}

// Bsdf::evaluate toward world wi. o: local_wo.
[[gnu::always_inline]] inline LobeValue coated_value(const Lobe& lobe, const V8& o, const V8& f, const V8& wi,
                                                    const CoatedMixture& mix) {
  const V8 i{dot(wi, lobe.s), dot(wi, lobe.t), dot(wi, lobe.n)};
  const M8 valid = mix.valid & consistent(wi, i.z, lobe.ng, lobe.wo_dot_ng, lobe.wo_z);
  const LobeValue v = mixture_value(o, i, f, mix);
  return {pick(valid, v.f_cos, V8{}), pick(valid, v.pdf, splat(0.0f))};
}

// GgxDistribution::sample_visible for o above the surface, from a point (p1, p2) on the unit disk
// (sample_uniform_disk_concentric's).
[[gnu::always_inline]] inline V8 ggx_sample_visible(const V8& o, F8 alpha, F8 p1, F8 p2) {
  const V8 v{alpha * o.x, alpha * o.y, o.z};
  const V8 vh = mul(v, splat(1.0f) / root(dot(v, v)));
  const F8 len2 = vh.x * vh.x + vh.y * vh.y;
  const F8 inv = splat(1.0f) / root(len2);
  const M8 tilted = len2 > 0;
  const V8 t1{pick(tilted, -vh.y * inv, splat(1.0f)), pick(tilted, vh.x * inv, splat(0.0f)),
              pick(tilted, splat(0.0f) * inv, splat(0.0f))};
  const V8 t2 = cross(vh, t1);
  const F8 s = splat(0.5f) * (splat(1.0f) + vh.z);
  p2 = (splat(1.0f) - s) * root(maximum(splat(0.0f), splat(1.0f) - p1 * p1)) + s * p2;
  const F8 up = root(maximum(splat(0.0f), splat(1.0f) - p1 * p1 - p2 * p2));
  const V8 nh = add(add(mul(t1, p1), mul(t2, p2)), mul(vh, up));
  const V8 m{alpha * nh.x, alpha * nh.y, maximum(splat(1e-7f), nh.z)};
  return mul(m, splat(1.0f) / root(dot(m, m)));
}

// Bsdf::sample of the mixture where lanes ask for it: the lobe u_lobe picks (metal, layer, diffuse,
// in Bsdf's order), its direction (the visible normal's reflection of o for the glossy lobes, else
// `diffuse`, the cosine-weighted direction drawn from the same disk point), its lobe's checks and
// Bsdf::sample's, and the value and density it gives: the mixture's, or where one lobe alone can be
// picked (Bsdf's only_lobe_), that lobe's. p1, p2: the disk point.
struct CoatedSample {
  V8 wi, f_cos;
  F8 pdf;
  M8 sampled;
};
[[gnu::always_inline]] inline CoatedSample coated_sample(const Lobe& lobe, const V8& o, const V8& f,
                                                         const CoatedMixture& mix, F8 u_lobe, F8 p1, F8 p2,
                                                         const V8& diffuse) {
  const M8 has_metal = mix.metal_pick > 0, has_coat = mix.coat_pick > 0, has_diffuse = mix.diffuse_pick > 0;
  // Each lobe with a pick extends the CDF; u_lobe below it picks the lobe, and past the end the last one.
  const F8 cdf_coat = mix.metal_pick + mix.coat_pick;
  const M8 in_metal = has_metal & ((u_lobe < mix.metal_pick) | (~has_coat & ~has_diffuse));
  const M8 in_coat = ~in_metal & has_coat & ((u_lobe < cdf_coat) | ~has_diffuse);
  const M8 in_diffuse = ~in_metal & ~in_coat & has_diffuse;
  const V8 wm = ggx_sample_visible(o, mix.alpha, p1, p2);
  const V8 reflected = sub(mul(wm, splat(2.0f) * dot(o, wm)), o);  // reflect(): -o + wm (2 o.wm)
  const GlossyValues glossy = glossy_values(o, reflected, mix);
  const F8 diffuse_pdf = maximum(diffuse.z, splat(0.0f)) * splat(kInvPi);  // Lambertian::pdf
  const M8 drawn = (in_metal & ~(o.z <= 0) & ~(reflected.z <= 0) & (glossy.metal_pdf > 0)) |
                   (in_coat & ~(reflected.z * o.z <= 0) & (glossy.coat_pdf > 0)) |
                   (in_diffuse & (o.z > 0) & (diffuse_pdf > 0));
  const V8 local = pick(in_diffuse, diffuse, reflected);
  const V8 wi = add(add(mul(lobe.s, local.x), mul(lobe.t, local.y)), mul(lobe.n, local.z));
  CoatedSample out;
  out.wi = wi;
  const LobeValue mixed = coated_value(lobe, o, f, wi, mix);
  // One lobe alone: its own value at the drawn direction, times its weight and |cos|, and its pick.
  const M8 alone = (has_metal & ~has_coat & ~has_diffuse) | (~has_metal & has_coat & ~has_diffuse) |
                   (~has_metal & ~has_coat & has_diffuse);
  const F8 cos = absolute(local.z);
  const F8 coat_f_cos = glossy.coat_f * (mix.coat_weight * cos);
  const V8 lone_f = pick(in_metal, mul(glossy.metal_f, mix.metallic * cos),
                         pick(in_coat, V8{coat_f_cos, coat_f_cos, coat_f_cos}, mul(f, mix.diffuse_weight * cos)));
  const F8 lone_pdf = pick(in_metal, mix.metal_pick * glossy.metal_pdf,
                           pick(in_coat, mix.coat_pick * glossy.coat_pdf, mix.diffuse_pick * diffuse_pdf));
  out.f_cos = pick(alone, lone_f, mixed.f_cos);
  out.pdf = pick(alone, lone_pdf, mixed.pdf);
  out.sampled = mix.valid & drawn & consistent(wi, local.z, lobe.ng, lobe.wo_dot_ng, lobe.wo_z) & (out.pdf > 0) &
                any_nonzero(out.f_cos);
  return out;
}

// A block's coated lanes (kCoatAlpha not 0): their mixtures, and wo in their frame (o), made where
// there are any.
struct Coats {
  M8 coated;
  CoatedMixture mix;
  V8 o;
};
template <class B>
[[gnu::always_inline]] inline Coats coats_of(const B& batch, int first, const Lobe& lobe) {
  Coats c{};
  const F8 alpha = row(batch, B::kCoatAlpha, first);
  c.coated = alpha != 0;
  if (!any(c.coated)) return c;
  c.mix = coated_mixture(lobe, alpha, row(batch, B::kCoatEta, first), row(batch, B::kMetallic, first),
                         rows(batch, B::kBaseColor, first), row(batch, B::kDiffuseAlbedo, first));
  c.o = local_wo(lobe, rows(batch, B::kWo, first));
  return c;
}

// The value of the lanes' surfaces toward wi: the Lambertian lobe's, or the coated mixture's
// (kCoated: the block may hold coated lanes).
template <bool kCoated>
[[gnu::always_inline]] inline LobeValue surface_value(const Lobe& lobe, const Coats& coats, const V8& f, const V8& wi) {
  const LobeValue lambertian = lambertian_value(lobe, f, wi);
  if (!kCoated || !any(coats.coated)) return lambertian;
  const LobeValue c = coated_value(lobe, coats.o, f, wi, coats.mix);
  return {pick(coats.coated, c.f_cos, lambertian.f_cos), pick(coats.coated, c.pdf, lambertian.pdf)};
}

}  // namespace lanes
}  // namespace prism
