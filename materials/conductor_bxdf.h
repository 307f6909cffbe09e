// ConductorBxdf: GGX-rough or mirror reflection with Schlick's coloured Fresnel, the metal lobe of
// glTF 2.0 Appendix B. wo is expected in the +z hemisphere (opaque surfaces are two-sided).
#pragma once

#include <optional>

#include "materials/bxdf_sample.h"
#include "materials/microfacet.h"

namespace prism {

class ConductorBxdf {
 public:
  ConductorBxdf(const Rgb& f0, float alpha) : f0_(f0), ggx_(alpha), smooth_(alpha < GgxDistribution::kSmoothAlpha) {}

  bool is_delta() const { return smooth_; }
  BxdfValue evaluate(const Vec3& wo, const Vec3& wi) const;
  Rgb f(const Vec3& wo, const Vec3& wi) const { return evaluate(wo, wi).f; }
  float pdf(const Vec3& wo, const Vec3& wi) const { return evaluate(wo, wi).pdf; }
  std::optional<BxdfSample> sample(const Vec3& wo, Vec2 u) const;
  // Reflectance at normal cosine cos_o, for choosing between lobes.
  Rgb reflectance(float cos_o) const;

 private:
  Rgb f0_;
  GgxDistribution ggx_;
  bool smooth_;
};

}  // namespace prism
