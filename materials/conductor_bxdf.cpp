#include "materials/conductor_bxdf.h"

#include <cmath>

#include "materials/fresnel.h"

namespace prism {

Rgb ConductorBxdf::reflectance(float cos_o) const { return fresnel_schlick(f0_, cos_o); }

Rgb ConductorBxdf::f(const Vec3& wo, const Vec3& wi) const {
  if (smooth_ || wo.z <= 0 || wi.z <= 0) return {};
  const Vec3 h = wo + wi;
  if (!(length_squared(h) > 0)) return {};
  const Vec3 wm = normalize(h);
  // Torrance-Sparrow: D G F / (4 cos_o cos_i).
  return fresnel_schlick(f0_, dot(wo, wm)) * (ggx_.D(wm) * ggx_.G(wo, wi) / (4.0f * wo.z * wi.z));
}

float ConductorBxdf::pdf(const Vec3& wo, const Vec3& wi) const {
  if (smooth_ || wo.z <= 0 || wi.z <= 0) return 0;
  const Vec3 h = wo + wi;
  if (!(length_squared(h) > 0)) return 0;
  const Vec3 wm = normalize(h);
  return ggx_.D_visible(wo, wm) / (4.0f * std::abs(dot(wo, wm)));
}

std::optional<BxdfSample> ConductorBxdf::sample(const Vec3& wo, Vec2 u) const {
  if (wo.z <= 0) return std::nullopt;
  BxdfSample s;
  if (smooth_) {
    s.wi = Vec3(-wo.x, -wo.y, wo.z);
    s.f = fresnel_schlick(f0_, wo.z) / wo.z;
    s.pdf = 1;
    s.delta = true;
    return s;
  }
  const Vec3 wm = ggx_.sample_visible(wo, u);
  s.wi = reflect(wo, wm);
  if (s.wi.z <= 0) return std::nullopt;
  s.f = f(wo, s.wi);
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0)) return std::nullopt;
  return s;
}

}  // namespace prism
