// lanes::coated_*: glTF's default dielectric (a GGX layer over a Lambertian lobe) evaluated and sampled in SIMD lanes.
#pragma once

#include "core/constants.h"
#include "integrators/lane_lambertian_lobe.h"
#include "integrators/lane_math.h"

namespace prism {

// A vertex whose Bsdf is the coated mixture alone (Bsdf::coated_only), beyond its LambertianSurface:
// the layer's GGX alpha (roughness^2) and relative index, and the diffuse lobe's albedo estimate
// for the lobe pick, max(luminance(base colour), 0.05).
struct CoatedSurface {
  float alpha = 0, eta = 1, diffuse_albedo = 0;
};

namespace lanes {

// What Bsdf's constructor makes of a coated mixture at wo: the layer reflects F(wo) and has weight
// 1, the diffuse lobe 1 - F(wo); each is picked in proportion to its albedo estimate. valid: the
// Bsdf's valid_.
struct CoatedMixture {
  F8 alpha, eta, diffuse_weight, coat_pick, diffuse_pick;
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

// The mixture's weights and picks (Bsdf::Bsdf, in its order) for lanes whose wo is above the lobe.
[[gnu::always_inline]] inline CoatedMixture coated_mixture(const Lobe& lobe, F8 alpha, F8 eta, F8 diffuse_albedo) {
  const F8 r = fresnel_dielectric_front(lobe.wo_z, eta);
  const F8 diffuse_weight = maximum(splat(0.0f), splat(1.0f) - r);
  const F8 coat = splat(0.2126f) * r + splat(0.7152f) * r + splat(0.0722f) * r;  // luminance(F) x weight 1
  const F8 diffuse = diffuse_weight * diffuse_albedo;
  const F8 total = coat + diffuse;
  const M8 valid = lobe.valid & (total > 0);
  return {alpha, eta, diffuse_weight, pick(valid, coat / total, splat(0.0f)), pick(valid, diffuse / total, splat(0.0f)),
          valid};
}

// GgxDistribution::lambda.
[[gnu::always_inline]] inline F8 ggx_lambda(const V8& w, F8 alpha) {
  const F8 c2 = w.z * w.z;
  const F8 tan2 = (w.x * w.x + w.y * w.y) / c2;
  return pick(c2 <= 0, splat(1e30f), splat(0.5f) * (root(splat(1.0f) + alpha * alpha * tan2) - splat(1.0f)));
}

// The layer's DielectricBxdf::evaluate (ReflectionOnly, its exact Fresnel curve) at local o and i:
// f (every channel's), and the density of the layer's sample() choosing i; zero where it reflects
// nothing.
struct LayerValue {
  F8 f, pdf;
};
[[gnu::always_inline]] inline LayerValue layer_value(const V8& o, const V8& i, F8 alpha, F8 eta) {
  // The half vector, turned to +z.
  const V8 h = add(o, i);
  const F8 len2 = dot(h, h);
  V8 wm = mul(h, splat(1.0f) / root(len2));
  wm = pick(wm.z < 0, negate(wm), wm);
  const F8 wm_o = dot(wm, o);
  const M8 reflects = (o.z * i.z > 0) & (len2 > 0) & ~(dot(wm, i) * i.z < 0) & ~(wm_o * o.z < 0);
  const F8 r = fresnel_dielectric_front(wm_o, eta);
  // D (Walter et al. 2007, eq. 33), height-correlated G, and the visible normals' density.
  const F8 a2 = alpha * alpha;
  const F8 c2 = wm.z * wm.z;
  const F8 t = (wm.x * wm.x + wm.y * wm.y) + c2 * a2;
  const F8 d = pick(c2 <= 0, splat(0.0f), a2 / (splat(kPi) * t * t));
  const F8 lambda_o = ggx_lambda(o, alpha), lambda_i = ggx_lambda(i, alpha);
  const F8 g = splat(1.0f) / (splat(1.0f) + lambda_o + lambda_i);
  const F8 cos_o = absolute(o.z), cos_i = absolute(i.z);
  const F8 f = r * (d * g / (splat(4.0f) * cos_i * cos_o));
  const F8 visible = splat(1.0f) / (splat(1.0f) + lambda_o) * maximum(splat(0.0f), absolute(wm_o)) * d / cos_o;
  return {pick(reflects, f, splat(0.0f)), pick(reflects, visible / (splat(4.0f) * absolute(wm_o)), splat(0.0f))};
}

// Bsdf::evaluate of the mixture, in its order: wi into the frame, consistent(), the layer's value,
// the Lambertian lobe's, then their sum by weight and by pick. wo: world; f: albedo / pi.
[[gnu::always_inline]] inline LobeValue coated_value(const Lobe& lobe, const V8& wo, const V8& f, const V8& wi,
                                                    const CoatedMixture& mix) {
  const V8 o{dot(wo, lobe.s), dot(wo, lobe.t), lobe.wo_z};
  const V8 i{dot(wi, lobe.s), dot(wi, lobe.t), dot(wi, lobe.n)};
  const M8 valid = mix.valid & consistent(wi, i.z, lobe.ng, lobe.wo_dot_ng, lobe.wo_z);
  const LayerValue layer = layer_value(o, i, mix.alpha, mix.eta);
  const M8 diffuse = (i.z > 0) & (o.z > 0);
  const V8 diffuse_f = pick(diffuse, f, V8{});
  const F8 diffuse_pdf = pick(diffuse, i.z * splat(kInvPi), splat(0.0f));
  const V8 sum = add(V8{layer.f, layer.f, layer.f}, mul(diffuse_f, mix.diffuse_weight));
  const F8 pdf = mix.coat_pick * layer.pdf + mix.diffuse_pick * diffuse_pdf;
  return {pick(valid, mul(sum, absolute(i.z)), V8{}), pick(valid, pdf, splat(0.0f))};
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

// Bsdf::sample of the mixture where lanes ask for it: the lobe u_lobe picks, its direction (the
// layer's visible normal reflecting o, or `diffuse`, the cosine-weighted direction drawn from the
// same disk point), Bsdf::sample's checks, and the value and density it gives (the mixture's; the
// layer's alone where the diffuse lobe cannot be picked). p1, p2: the disk point.
struct CoatedSample {
  V8 wi, f_cos;
  F8 pdf;
  M8 sampled;
};
[[gnu::always_inline]] inline CoatedSample coated_sample(const Lobe& lobe, const V8& wo, const V8& f,
                                                         const CoatedMixture& mix, F8 u_lobe, F8 p1, F8 p2,
                                                         const V8& diffuse) {
  const V8 o{dot(wo, lobe.s), dot(wo, lobe.t), lobe.wo_z};
  const M8 in_layer = u_lobe < mix.coat_pick;
  const V8 wm = ggx_sample_visible(o, mix.alpha, p1, p2);
  const V8 reflected = sub(mul(wm, splat(2.0f) * dot(o, wm)), o);  // reflect(): -o + wm (2 o.wm)
  const LayerValue layer = layer_value(o, reflected, mix.alpha, mix.eta);
  const M8 drawn = (in_layer & ~(reflected.z * o.z <= 0) & (layer.pdf > 0)) |
                   (~in_layer & (o.z > 0) & (maximum(diffuse.z, splat(0.0f)) * splat(kInvPi) > 0));
  const V8 local = pick(in_layer, reflected, diffuse);
  const V8 wi = add(add(mul(lobe.s, local.x), mul(lobe.t, local.y)), mul(lobe.n, local.z));
  CoatedSample out;
  out.wi = wi;
  const LobeValue both = coated_value(lobe, wo, f, wi, mix);
  // Where only the layer can be picked (Bsdf's only_lobe_), its own value and density.
  const M8 alone = mix.diffuse_pick == 0;
  const F8 layer_f_cos = layer.f * absolute(local.z);
  out.f_cos = pick(alone, V8{layer_f_cos, layer_f_cos, layer_f_cos}, both.f_cos);
  out.pdf = pick(alone, mix.coat_pick * layer.pdf, both.pdf);
  out.sampled = mix.valid & drawn & consistent(wi, local.z, lobe.ng, lobe.wo_dot_ng, lobe.wo_z) & (out.pdf > 0) &
                any_nonzero(out.f_cos);
  return out;
}

// A block's coated lanes (kCoatAlpha not 0): their mixtures, and wo, made where there are any.
struct Coats {
  M8 coated;
  CoatedMixture mix;
  V8 wo;
};
template <class B>
[[gnu::always_inline]] inline Coats coats_of(const B& batch, int first, const Lobe& lobe) {
  Coats c{};
  const F8 alpha = row(batch, B::kCoatAlpha, first);
  c.coated = alpha != 0;
  if (!any(c.coated)) return c;
  c.mix = coated_mixture(lobe, alpha, row(batch, B::kCoatEta, first), row(batch, B::kDiffuseAlbedo, first));
  c.wo = rows(batch, B::kWo, first);
  return c;
}

// The value of the lanes' surfaces toward wi: the Lambertian lobe's, or the coated mixture's
// (kCoated: the block may hold coated lanes).
template <bool kCoated>
[[gnu::always_inline]] inline LobeValue surface_value(const Lobe& lobe, const Coats& coats, const V8& f, const V8& wi) {
  const LobeValue lambertian = lambertian_value(lobe, f, wi);
  if (!kCoated || !any(coats.coated)) return lambertian;
  const LobeValue c = coated_value(lobe, coats.wo, f, wi, coats.mix);
  return {pick(coats.coated, c.f_cos, lambertian.f_cos), pick(coats.coated, c.pdf, lambertian.pdf)};
}

}  // namespace lanes
}  // namespace prism
