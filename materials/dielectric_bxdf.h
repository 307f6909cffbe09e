// DielectricBxdf: reflection and transmission at a dielectric interface (smooth or GGX-rough,
// Walter et al., "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007), with exact
// Fresnel, optional thin-walled transmission, and a reflection-only mode for coats.
#pragma once

#include <optional>

#include "materials/bxdf_sample.h"
#include "materials/microfacet.h"

namespace prism {

class DielectricBxdf {
 public:
  enum class Mode {
    Volume,         // a boundary between two media: transmission refracts
    ThinWalled,     // an infinitely thin sheet: transmission passes straight through
    ReflectionOnly  // the specular layer of an opaque dielectric (a coat)
  };

  // eta = n_back / n_front (+z is the front); alpha = roughness^2; tint multiplies transmission.
  DielectricBxdf(float eta, float alpha, const Rgb& tint, Mode mode)
      : eta_(eta), ggx_(alpha), smooth_(alpha < GgxDistribution::kSmoothAlpha), tint_(tint), mode_(mode) {}

  // KHR_materials_specular: the reflectance curve is remapped from F0 to a tinted F0 x colour
  // (capped at 1) and scaled by `weight`; transmission gets 1 - max(F) (glTF's fresnel_mix).
  // (1, white) leaves the exact curve.
  void set_specular(float weight, const Rgb& color) {
    spec_weight_ = weight;
    spec_color_ = color;
  }
  // Reflectance with the specular remapping, per channel.
  Rgb reflectance_rgb(float cos_o) const;

  bool is_delta() const { return smooth_ || eta_ == 1.0f; }
  BxdfValue evaluate(const Vec3& wo, const Vec3& wi) const;
  Rgb f(const Vec3& wo, const Vec3& wi) const { return evaluate(wo, wi).f; }
  float pdf(const Vec3& wo, const Vec3& wi) const { return evaluate(wo, wi).pdf; }
  std::optional<BxdfSample> sample(const Vec3& wo, float u_lobe, Vec2 u) const;

  // A smooth thin sheet's delta transmission: what passes straight through along -wo (tint x
  // (1 - R)), the expectation of sample()'s transmitted branch. Zero for rough sheets, volume
  // boundaries and coats, whose transmission bends light or is absent.
  Rgb straight_transmittance(float cos_o) const {
    if (mode_ != Mode::ThinWalled || !is_delta()) return {};
    return tint_ * (1.0f - split(cos_o).scalar);
  }

  // Reflectance of the interface at cosine cos_o from the front (+) or back (-); for thin walls
  // it includes the light reflected back and forth inside the sheet.
  float reflectance(float cos_o) const;

 private:
  // The reflectance that reflects (per channel) and the scalar that splits reflection from
  // transmission (its largest channel; the plain Fresnel value without specular).
  struct Split {
    Rgb reflect;
    float scalar;
  };
  Split split(float cos_o) const;

  // Microfacet normal for a reflection or refraction pair, in the +z hemisphere; false if none.
  bool half_vector(const Vec3& wo, const Vec3& wi, Vec3& wm, float& etap) const;

  float eta_;
  GgxDistribution ggx_;
  bool smooth_;
  Rgb tint_;
  Mode mode_;
  float spec_weight_ = 1;
  Rgb spec_color_{1, 1, 1};
};

}  // namespace prism
