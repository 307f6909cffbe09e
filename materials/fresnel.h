// Fresnel reflectance (exact unpolarised for dielectrics, Schlick for glTF metals) and the laws of
// reflection and refraction, in any frame.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/vec3.h"

namespace prism {

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
  const float sin2_i = std::max(0.0f, 1.0f - cos_i * cos_i);
  const float sin2_t = sin2_i / (eta * eta);
  if (sin2_t >= 1.0f) return {1.0f, 1.0f};
  const float cos_t = std::sqrt(std::max(0.0f, 1.0f - sin2_t));
  const float r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const float r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
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
  const float c2_sq = 1.0f - inv * inv * std::max(0.0f, 1.0f - c1 * c1);
  if (c2_sq <= 0.0f) return false;  // TIR (c2^2 < 0; = 0 is the grazing limit)
  wt = -wo * inv + n * (inv * c1 - std::sqrt(c2_sq));
  return true;
}

}  // namespace prism
