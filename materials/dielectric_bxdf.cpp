#include "materials/dielectric_bxdf.h"

#include <algorithm>
#include <cmath>

#include "materials/fresnel.h"

namespace prism {
namespace {

inline Vec3 flip_z(const Vec3& v) { return {v.x, v.y, -v.z}; }

}  // namespace

float DielectricBxdf::reflectance(float cos_o) const {
  if (mode_ != Mode::ThinWalled) return fresnel_dielectric(cos_o, eta_);
  // Both faces of a thin sheet border the same medium: symmetric, and never totally reflecting.
  const float r = fresnel_dielectric(std::abs(cos_o), eta_);
  // A sheet reflects r at the first face plus t r t + t r^3 t + ... from inside (a geometric
  // series), so R = r + t^2 r / (1 - r^2) with t = 1 - r.
  const float t = 1.0f - r;
  return r < 1.0f ? r + t * t * r / (1.0f - r * r) : 1.0f;
}

Rgb DielectricBxdf::reflectance_rgb(float cos_o) const {
  const float r = reflectance(cos_o);
  if (spec_weight_ == 1.0f && spec_color_ == Rgb(1.0f)) return Rgb(r);
  // Where the exact curve sits between its F0 and 1, the tinted curve sits between F0 x colour
  // and 1 (how glTF's specular colour scales F0 while grazing reflection stays white).
  const float f0 = ((eta_ - 1) / (eta_ + 1)) * ((eta_ - 1) / (eta_ + 1));
  const float w = f0 < 1.0f ? std::clamp((r - f0) / (1.0f - f0), 0.0f, 1.0f) : 1.0f;
  const Rgb f0_tinted = min(spec_color_ * f0, Rgb(1.0f));
  return (f0_tinted + (Rgb(1.0f) - f0_tinted) * w) * spec_weight_;
}

DielectricBxdf::Split DielectricBxdf::split(float cos_o) const {
  if (spec_weight_ == 1.0f && spec_color_ == Rgb(1.0f)) {
    const float r = reflectance(cos_o);
    return {Rgb(r), r};
  }
  const Rgb rc = reflectance_rgb(cos_o);
  return {rc, std::min(1.0f, max_component(rc))};
}

bool DielectricBxdf::half_vector(const Vec3& wo, const Vec3& wi, Vec3& wm, float& etap) const {
  const float cos_o = wo.z, cos_i = wi.z;
  if (cos_o == 0 || cos_i == 0) return false;
  const bool reflect = cos_o * cos_i > 0;
  if (reflect || mode_ == Mode::ThinWalled) {
    // Thin walls transmit along the mirror image of the reflected direction.
    etap = 1.0f;
    wm = wo + (reflect ? wi : flip_z(wi));
  } else {
    etap = cos_o > 0 ? eta_ : 1.0f / eta_;
    wm = wi * etap + wo;  // generalised half vector (Walter et al. eq. 16)
  }
  const float len2 = length_squared(wm);
  if (!(len2 > 0)) return false;
  wm = face_forward(wm / std::sqrt(len2), Vec3(0, 0, 1));
  return true;
}

BxdfValue DielectricBxdf::evaluate(const Vec3& wo, const Vec3& wi) const {
  if (is_delta()) return {};
  const bool reflect = wo.z * wi.z > 0;
  if (!reflect && mode_ == Mode::ReflectionOnly) return {};
  Vec3 wm;
  float etap;
  if (!half_vector(wo, wi, wm, etap)) return {};
  const Vec3 wi_m = (reflect || mode_ != Mode::ThinWalled) ? wi : flip_z(wi);
  // Microfacets seen from behind contribute nothing.
  if (dot(wm, wi_m) * wi_m.z < 0 || dot(wm, wo) * wo.z < 0) return {};
  const Split F = split(dot(wo, wm));
  const float R = F.scalar;
  const float d = ggx_.D(wm), lambda_o = ggx_.lambda(wo);
  const float cos_o = std::abs(wo.z), cos_i = std::abs(wi.z);
  BxdfValue v;
  // The density: reflection or transmission chosen by Fresnel, then the visible normals' density
  // mapped to wi.
  const float pr = mode_ == Mode::ReflectionOnly ? 1.0f : R;
  const float pt = mode_ == Mode::ReflectionOnly ? 0.0f : 1.0f - R;
  if (reflect || mode_ == Mode::ThinWalled) {
    const float g = GgxDistribution::G(lambda_o, ggx_.lambda(wi_m));
    v.f = reflect ? F.reflect * (d * g / (4.0f * cos_i * cos_o)) : tint_ * (d * g * (1.0f - R) / (4.0f * cos_i * cos_o));
    // dwm/dwi = 1 / (4 |wo.wm|) for the mirror direction.
    if (!(pr + pt <= 0))
      v.pdf = GgxDistribution::D_visible(wo, wm, d, lambda_o) / (4.0f * std::abs(dot(wo, wm))) * (reflect ? pr : pt) /
              (pr + pt);
    return v;
  }
  // Walter et al. eq. 21, with radiance scaled by 1 / etap^2 crossing the boundary.
  const float denom = dot(wi, wm) + dot(wo, wm) / etap;
  const float ft = d * GgxDistribution::G(lambda_o, ggx_.lambda(wi)) * (1.0f - R) *
                   std::abs(dot(wi, wm) * dot(wo, wm) / (cos_i * cos_o * denom * denom));
  v.f = tint_ * (ft / (etap * etap));
  const float dwm_dwi = std::abs(dot(wi, wm)) / (denom * denom);
  if (!(pr + pt <= 0)) v.pdf = GgxDistribution::D_visible(wo, wm, d, lambda_o) * dwm_dwi * pt / (pr + pt);
  return v;
}

std::optional<BxdfSample> DielectricBxdf::sample(const Vec3& wo, float u_lobe, Vec2 u) const {
  if (wo.z == 0) return std::nullopt;
  if (is_delta()) {
    // Smooth interface: mirror reflection or refraction, chosen in proportion to Fresnel.
    const Split F = split(wo.z);
    const float R = F.scalar;
    const float pr = R, pt = mode_ == Mode::ReflectionOnly ? 0.0f : 1.0f - R;
    if (pr + pt <= 0) return std::nullopt;
    const float cos_o = std::abs(wo.z);
    BxdfSample s;
    s.delta = true;
    if (u_lobe < pr / (pr + pt)) {
      s.wi = Vec3(-wo.x, -wo.y, wo.z);
      s.pdf = pr / (pr + pt);
      s.f = F.reflect / cos_o;
      return s;
    }
    s.transmission = true;
    s.pdf = pt / (pr + pt);
    if (mode_ == Mode::ThinWalled || eta_ == 1.0f) {
      s.wi = -wo;
      s.f = tint_ * ((1.0f - R) / cos_o);
      return s;
    }
    const float etap = wo.z > 0 ? eta_ : 1.0f / eta_;
    if (!refract(wo, Vec3(0, 0, wo.z > 0 ? 1.0f : -1.0f), etap, s.wi)) return std::nullopt;
    s.eta = etap;
    s.f = tint_ * ((1.0f - R) / std::abs(s.wi.z) / (etap * etap));
    return s;
  }

  const Vec3 wm = ggx_.sample_visible(wo, u);  // in wo's hemisphere
  // Fresnel takes the cosine against the +z-facing normal: negative from the back (eta inverts).
  const float R = split(dot(wo, wm.z < 0 ? -wm : wm)).scalar;
  const float pr = mode_ == Mode::ReflectionOnly ? 1.0f : R;
  const float pt = mode_ == Mode::ReflectionOnly ? 0.0f : 1.0f - R;
  BxdfSample s;
  if (u_lobe < pr / (pr + pt)) {
    s.wi = reflect(wo, wm);
    if (s.wi.z * wo.z <= 0) return std::nullopt;
  } else if (mode_ == Mode::ThinWalled) {
    s.wi = flip_z(reflect(wo, wm));
    if (s.wi.z * wo.z >= 0) return std::nullopt;
    s.transmission = true;
  } else {
    const float etap = wo.z > 0 ? eta_ : 1.0f / eta_;
    if (!refract(wo, wm, etap, s.wi) || s.wi.z * wo.z >= 0) return std::nullopt;
    s.transmission = true;
    s.eta = etap;
  }
  const BxdfValue v = evaluate(wo, s.wi);
  s.f = v.f;
  s.pdf = v.pdf;
  if (!(s.pdf > 0)) return std::nullopt;
  return s;
}

}  // namespace prism
