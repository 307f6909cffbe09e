#include "materials/conductor_bxdf.h"

#include <cmath>

#include "materials/fresnel.h"

namespace prism {

Rgb ConductorBxdf::reflectance(float cos_o) const { return fresnel_schlick(f0_, cos_o); }

BxdfValue ConductorBxdf::evaluate(const Vec3& wo, const Vec3& wi) const {
  if (smooth_ || wo.z <= 0 || wi.z <= 0) return {};
  const Vec3 h = wo + wi;
  if (!(length_squared(h) > 0)) return {};
  const Vec3 wm = normalize(h);
  const float d = ggx_.D(wm), lambda_o = ggx_.lambda(wo);
  // Torrance-Sparrow: D G F / (4 cos_o cos_i); density: the visible normals', reflected.
  return {fresnel_schlick(f0_, dot(wo, wm)) * (d * GgxDistribution::G(lambda_o, ggx_.lambda(wi)) / (4.0f * wo.z * wi.z)),
          GgxDistribution::D_visible(wo, wm, d, lambda_o) / (4.0f * std::abs(dot(wo, wm)))};
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
  const BxdfValue v = evaluate(wo, s.wi);
  s.f = v.f;
  s.pdf = v.pdf;
  if (!(s.pdf > 0)) return std::nullopt;
  return s;
}

}  // namespace prism
