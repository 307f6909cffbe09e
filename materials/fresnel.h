// Fresnel reflectance (exact unpolarised for dielectrics, Schlick for glTF metals) and the laws of
// reflection and refraction, in any frame.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/vec3.h"

namespace prism {

// eta^2 cos_t^2 = eta^2 - sin_i^2 for light at cosine cos_i (>= 0) refracting into relative index
// eta (Snell: sin_t = sin_i / eta); zero or below means total internal reflection. Written as
// (eta - 1)(eta + 1) + cos_i^2 so it stays accurate at grazing angles and near the critical
// angle, and shared by Fresnel and refraction so both agree on where TIR begins.
inline float refracted_cos2_scaled(float cos_i, float eta) { return (eta - 1.0f) * (eta + 1.0f) + cos_i * cos_i; }

struct FresnelSP {
  float s = 1, p = 1;  // reflectance of s- (perpendicular) and p- (parallel) polarised light
};

// Reflectance at a dielectric interface for each polarisation. cos_i is the cosine of the
// incident angle on the side the light comes from (negative: from the back, where the relative
// index is inverted); eta = n_back / n_front. Total internal reflection gives 1 (Hecht, Optics §4.6).
inline FresnelSP fresnel_dielectric_sp(float cos_i, float eta) {
  if (eta == 1.0f) return {0.0f, 0.0f};  // no interface at all: exactly invisible
  cos_i = std::clamp(cos_i, -1.0f, 1.0f);
  if (cos_i < 0) {
    eta = 1.0f / eta;
    cos_i = -cos_i;
  }
  // (eta cos_t)^2 = eta^2 - sin_i^2 = (eta - 1)(eta + 1) + cos_i^2. Forming 1 - cos_i^2 first
  // rounds sin_i^2 to 2^-24 absolute, and at grazing incidence on an index close to 1 (or near a
  // critical angle) the next subtraction cancels: R was off by 5e-4 relative at IOR 1.0001 from
  // what any input within 4 ulps gives. Here the cancellation is between two terms that are each
  // exact to a few ulps (docs/NUMERICS.md; tests/extremes/test_dielectric_extremes.cpp).
  const float eta2_cos2_t = refracted_cos2_scaled(cos_i, eta);
  if (eta2_cos2_t <= 0.0f) return {1.0f, 1.0f};
  const float eta_cos_t = std::sqrt(eta2_cos2_t);
  const float eta2_cos_i = eta * eta * cos_i;
  const float r_s = (cos_i - eta_cos_t) / (cos_i + eta_cos_t);
  const float r_p = (eta2_cos_i - eta_cos_t) / (eta2_cos_i + eta_cos_t);  // (eta cos_i - cos_t) x eta over the same
  return {r_s * r_s, r_p * r_p};
}

// Unpolarised reflectance: the mean of both polarisations.
inline float fresnel_dielectric(float cos_i, float eta) {
  const FresnelSP f = fresnel_dielectric_sp(cos_i, eta);
  return 0.5f * (f.s + f.p);
}

// Schlick's approximation with a coloured F0, as glTF 2.0 Appendix B defines for metals.
inline Rgb fresnel_schlick(const Rgb& f0, float cos_i) {
  const float m = std::clamp(1.0f - std::abs(cos_i), 0.0f, 1.0f);
  const float m5 = (m * m) * (m * m) * m;
  return f0 + (Rgb(1.0f) - f0) * m5;
}

inline Vec3 reflect(const Vec3& wo, const Vec3& n) { return -wo + n * (2.0f * dot(wo, n)); }

// Refracts wo (pointing away from the surface, on the side n points to) through an interface with
// relative index eta = n_t / n_i. Returns false on total internal reflection. With c1 = cos_i and
// c2 = cos_t: wt = -wo / eta + (c1 / eta - c2) n  (the seed lectures' T = eta' I + (eta' c1 - c2) N
// with eta' = 1 / eta and I = -wo).
inline bool refract(const Vec3& wo, const Vec3& n, float eta, Vec3& wt) {
  const float c1 = dot(wo, n);
  const float inv = 1.0f / eta;
  const float eta2_c2_sq = refracted_cos2_scaled(std::min(std::abs(c1), 1.0f), eta);
  if (eta2_c2_sq <= 0.0f) return false;  // TIR (c2^2 < 0; = 0 is the grazing limit)
  wt = -wo * inv + n * (inv * c1 - std::sqrt(eta2_c2_sq) * inv);
  return true;
}

}  // namespace prism
