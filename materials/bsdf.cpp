#include "materials/bsdf.h"

#include <algorithm>
#include <cmath>

namespace prism {

Bsdf::Facing Bsdf::facing(const Vec3& ns, const Vec3& ng, const Vec3& wo, bool volume_boundary) {
  Facing f;
  const float side = dot(wo, ng);
  f.valid = side != 0;
  // Two-sided surfaces look the same from both faces: mirror the frame to wo's side.
  const bool mirror = !volume_boundary && side < 0;
  f.ng = mirror ? -ng : ng;
  Vec3 n = mirror ? -ns : ns;
  if (dot(n, f.ng) < 0) n = -n;  // a shading normal facing into the surface: keep its side right
  // Interpolated normals can put wo below the shading hemisphere near silhouettes although it is
  // above the surface: the BSDF would be zero there (black rims). Bend the shading normal toward
  // wo just enough that wo sits above it again, by at most what the geometry allows.
  f.wo_dot_ng = dot(wo, f.ng);
  const float s_side = f.wo_dot_ng < 0 ? -1.0f : 1.0f;  // +1 once two-sided surfaces are mirrored
  const Vec3 n_side = n * s_side;
  const float threshold = std::min(0.9f * std::abs(side), 0.01f);
  if (f.valid && dot(wo, n_side) < threshold) {
    const Vec3 bent = n_side + wo * (threshold - dot(wo, n_side));
    if (length_squared(bent) > 0) n = normalize(bent) * s_side;
  }
  f.n = n;
  return f;
}

DielectricBxdf Bsdf::dielectric_lobe(const SurfaceParams& p, float eta, float alpha) {
  DielectricBxdf d(eta, alpha, p.base_color,
                   p.thin_walled ? DielectricBxdf::Mode::ThinWalled : DielectricBxdf::Mode::Volume);
  d.set_specular(std::max(0.0f, p.specular), max(p.specular_color, Rgb(0.0f)));
  return d;
}

Bsdf::Bsdf(const SurfaceParams& p, const Vec3& ns, const Vec3& ng, const Vec3& wo, float eta) : diffuse_{p.base_color} {
  const Facing f = facing(ns, ng, wo, p.transmission > 0 && !p.thin_walled);
  valid_ = f.valid;
  ng_ = f.ng;
  wo_dot_ng_ = f.wo_dot_ng;
  frame_ = Frame::from_normal(f.n);
  wo_ = frame_.to_local(wo);
  if (wo_.z == 0) valid_ = false;

  // The Lambertian lobe alone has weight and pick probability 1.
  if (lambertian_only(p, eta)) {
    lambertian_ = true;
    weight_[kDiffuse] = pick_[kDiffuse] = 1;
    only_lobe_ = kDiffuse;
    if (wo_.z < 0) valid_ = false;  // only a volume boundary is seen from below
    return;
  }
  // The other lobes are built only here: a plain diffuse surface does not pay for them.
  const float m = std::clamp(p.metallic, 0.0f, 1.0f), t = std::clamp(p.transmission, 0.0f, 1.0f);
  const float alpha = p.roughness * p.roughness;
  metal_.emplace(p.base_color, alpha);
  dielectric_.emplace(dielectric_lobe(p, eta, alpha));
  coat_.emplace(eta, alpha, Rgb(1.0f), DielectricBxdf::Mode::ReflectionOnly);
  coat_->set_specular(std::max(0.0f, p.specular), max(p.specular_color, Rgb(0.0f)));
  // glTF's fresnel_mix: the layer reflects F (per channel), the base below gets 1 - max(F).
  const Rgb F = m < 1 && t < 1 ? coat_->reflectance_rgb(wo_.z) : Rgb(0.0f);
  weight_[kMetal] = m;
  weight_[kDielectric] = (1 - m) * t;
  weight_[kCoat] = (1 - m) * (1 - t);
  weight_[kDiffuse] = (1 - m) * (1 - t) * std::max(0.0f, 1 - max_component(F));
  // Choose lobes by their albedo estimate at wo.
  float pick[kLobes] = {m > 0 ? m * std::max(luminance(metal_->reflectance(wo_.z)), 0.05f) : 0.0f, weight_[kDielectric],
                        weight_[kCoat] * luminance(F), weight_[kDiffuse] * std::max(luminance(p.base_color), 0.05f)};
  if (wo_.z < 0) pick[kMetal] = pick[kCoat] = pick[kDiffuse] = 0;  // only a volume boundary is seen from below
  float total = 0;
  for (float v : pick) total += v;
  if (!(total > 0)) valid_ = false;
  delta_only_ = true;
  int non_delta = 0;
  for (int k = 0; k < kLobes; ++k) {
    pick_[k] = total > 0 ? pick[k] / total : 0;
    if (pick_[k] > 0 && !lobe_is_delta(k)) {
      delta_only_ = false;
      ++non_delta;
      only_lobe_ = k;
    }
  }
  if (non_delta != 1) only_lobe_ = -1;
}

// The constructor's steps as far as they bear on the dielectric lobe: the same facing and cosine,
// the same lobe and weight. Its pick is that weight over a sum that includes it, so it is positive
// exactly where the weight is.
Rgb Bsdf::straight_through(const SurfaceParams& p, const Vec3& ns, const Vec3& ng, const Vec3& wo, float eta) {
  if (lambertian_only(p, eta)) return {};  // no dielectric lobe
  const Facing f = facing(ns, ng, wo, p.transmission > 0 && !p.thin_walled);
  const float cos_o = dot(wo, f.n);  // the frame's local wo.z
  if (!f.valid || cos_o == 0) return {};
  const float m = std::clamp(p.metallic, 0.0f, 1.0f), t = std::clamp(p.transmission, 0.0f, 1.0f);
  const float weight = (1 - m) * t;
  if (!(weight > 0)) return {};
  return dielectric_lobe(p, eta, p.roughness * p.roughness).straight_transmittance(cos_o) * weight;
}

bool Bsdf::lobe_is_delta(int lobe) const {
  switch (lobe) {
    case kMetal: return metal_->is_delta();
    case kDielectric: return dielectric_->is_delta();
    case kCoat: return coat_->is_delta();
    default: return false;
  }
}

BxdfValue Bsdf::lobe_value(int lobe, const Vec3& wi) const {
  switch (lobe) {
    case kMetal: return metal_->evaluate(wo_, wi);
    case kDielectric: return dielectric_->evaluate(wo_, wi);
    case kCoat: return coat_->evaluate(wo_, wi);
    default:
      if (wi.z > 0 && wo_.z > 0) return {diffuse_.f(), Lambertian::pdf(wi)};
      return {};
  }
}

// Shading and geometric normals must agree on whether wi reflects or transmits, or light would
// leak through the surface (Veach 1997, §5.3).
bool Bsdf::consistent(const Vec3& wi_world, const Vec3& wi_local) const {
  const float geometric = dot(wi_world, ng_) * wo_dot_ng_;
  const float shading = wi_local.z * wo_.z;
  return geometric != 0 && shading != 0 && ((geometric > 0) == (shading > 0));
}

Bsdf::Value Bsdf::evaluate(const Vec3& wi_world) const {
  if (!valid_ || delta_only_) return {};
  const Vec3 wi = frame_.to_local(wi_world);
  if (!consistent(wi_world, wi)) return {};
  if (only_lobe_ >= 0) {
    const BxdfValue l = lobe_value(only_lobe_, wi);
    return {l.f * (weight_[only_lobe_] * std::abs(wi.z)), pick_[only_lobe_] * l.pdf};
  }
  Value v;
  for (int k = 0; k < kLobes; ++k) {
    if (lobe_is_delta(k) || !(weight_[k] > 0 || pick_[k] > 0)) continue;
    const BxdfValue l = lobe_value(k, wi);
    if (weight_[k] > 0) v.f_cos += l.f * weight_[k];
    if (pick_[k] > 0) v.pdf += pick_[k] * l.pdf;
  }
  v.f_cos *= std::abs(wi.z);
  return v;
}

std::optional<BsdfSample> Bsdf::sample(float u_lobe, Vec2 u) const {
  if (!valid_) return std::nullopt;
  if (lambertian_) {
    const Vec3 wi = Lambertian::sample(u);
    BsdfSample out;
    out.wi = frame_.to_world(wi);
    out.pdf = Lambertian::pdf(wi);
    out.f_cos = diffuse_.f() * std::abs(wi.z);
    if (!(out.pdf > 0) || !consistent(out.wi, wi) || is_black(out.f_cos)) return std::nullopt;
    return out;
  }
  // Pick a lobe, then rescale u_lobe to reuse it inside the lobe.
  int lobe = -1;
  float start = 0, cdf = 0;
  for (int k = 0; k < kLobes; ++k) {
    if (pick_[k] <= 0) continue;
    lobe = k;
    start = cdf;
    cdf += pick_[k];
    if (u_lobe < cdf) break;
  }
  if (lobe < 0) return std::nullopt;
  const float u_inner = std::clamp((u_lobe - start) / pick_[lobe], 0.0f, 0x1.fffffep-1f);

  std::optional<BxdfSample> s;
  switch (lobe) {
    case kMetal: s = metal_->sample(wo_, u); break;
    case kDielectric: s = dielectric_->sample(wo_, u_inner, u); break;
    case kCoat: s = coat_->sample(wo_, u_inner, u); break;
    default:
      if (wo_.z > 0) s = BxdfSample{Lambertian::sample(u), diffuse_.f(), 0, false, false, 1};
      if (s) s->pdf = Lambertian::pdf(s->wi);
  }
  if (!s || !(s->pdf > 0)) return std::nullopt;
  BsdfSample out;
  out.wi = frame_.to_world(s->wi);
  out.delta = s->delta;
  out.transmission = s->transmission;
  out.eta = s->eta;
  if (!consistent(out.wi, s->wi)) return std::nullopt;
  if (s->delta || lobe == only_lobe_) {
    // A delta lobe, or the only non-delta one: the mixture's value and density are this lobe's.
    out.f_cos = s->f * (weight_[lobe] * std::abs(s->wi.z));
    out.pdf = pick_[lobe] * s->pdf;
  } else {
    const Value v = evaluate(out.wi);
    out.f_cos = v.f_cos;
    out.pdf = v.pdf;
  }
  if (!(out.pdf > 0) || is_black(out.f_cos)) return std::nullopt;
  return out;
}

}  // namespace prism
