// The GGX / Trowbridge-Reitz microfacet distribution with height-correlated Smith masking and
// sampling of visible normals (Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 2018).
#pragma once

#include <cmath>

#include "core/constants.h"
#include "core/sampling.h"
#include "core/vec3.h"

namespace prism {

// Isotropic GGX in the local frame (+z the macro normal), alpha = glTF roughness^2.
class GgxDistribution {
 public:
  // Below this alpha the surface is treated as perfectly smooth (delta lobes), as pbrt-v4 does:
  // narrower lobes exceed what float directions resolve.
  static constexpr float kSmoothAlpha = 1e-3f;

  explicit GgxDistribution(float alpha) : alpha_(std::max(alpha, kSmoothAlpha)) {}
  float alpha() const { return alpha_; }

  // Normal distribution D(wm) (Walter et al. 2007, eq. 33) for a unit wm, with its denominator
  // cos^2 (a^2 - 1) + 1 written as sin^2 + cos^2 a^2: the former cancels to 0 in float at the
  // peak once a^2 is below half an ulp of 1.
  float D(const Vec3& wm) const {
    const float c2 = wm.z * wm.z;
    if (c2 <= 0) return 0;
    const float a2 = alpha_ * alpha_;
    const float t = (wm.x * wm.x + wm.y * wm.y) + c2 * a2;
    return a2 / (kPi * t * t);
  }

  // Smith's Lambda for GGX (Heitz 2014, "Understanding the Masking-Shadowing Function", eq. 72).
  float lambda(const Vec3& w) const {
    const float c2 = w.z * w.z;
    if (c2 <= 0) return 1e30f;
    const float tan2 = (w.x * w.x + w.y * w.y) / c2;  // not (1 - c2) / c2: no cancellation near the pole
    return 0.5f * (std::sqrt(1.0f + alpha_ * alpha_ * tan2) - 1.0f);
  }
  float G1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }
  // Height-correlated masking-shadowing (Heitz 2014, eq. 99), from the two directions' Lambdas.
  static float G(float lambda_o, float lambda_i) { return 1.0f / (1.0f + lambda_o + lambda_i); }
  float G(const Vec3& wo, const Vec3& wi) const { return G(lambda(wo), lambda(wi)); }

  // Distribution of normals visible from w: G1(w) max(0, w.wm) D(wm) / |w.z|, given D(wm) and
  // lambda(w) where they are at hand.
  static float D_visible(const Vec3& w, const Vec3& wm, float d, float lambda_w) {
    const float cos_o = std::abs(w.z);
    if (cos_o == 0) return 0;
    return 1.0f / (1.0f + lambda_w) * std::max(0.0f, std::abs(dot(w, wm))) * d / cos_o;
  }
  float D_visible(const Vec3& w, const Vec3& wm) const { return D_visible(w, wm, D(wm), lambda(w)); }

  // A microfacet normal distributed as D_visible(w, .), for w in either hemisphere (the result is
  // in w's hemisphere).
  Vec3 sample_visible(const Vec3& w, Vec2 u) const {
    const bool flip = w.z < 0;
    const Vec3 wo = flip ? -w : w;
    // Stretch to the hemisphere configuration of a unit-roughness distribution.
    const Vec3 vh = normalize(Vec3(alpha_ * wo.x, alpha_ * wo.y, wo.z));
    const float len2 = vh.x * vh.x + vh.y * vh.y;
    const Vec3 t1 = len2 > 0 ? Vec3(-vh.y, vh.x, 0) / std::sqrt(len2) : Vec3(1, 0, 0);
    const Vec3 t2 = cross(vh, t1);
    // Uniform point on the projected disk, warped to the visible half. The disk point is Shirley and
    // Chiu's concentric map's rather than Heitz's polar one (both uniform): it keeps the draws'
    // stratification, and its sine and cosine are the SIMD lanes' bits too (lane_coated_lobe.h).
    const Vec2 d = sample_uniform_disk_concentric(u);
    const float p1 = d.x;
    float p2 = d.y;
    const float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
    const Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2));
    // Unstretch.
    Vec3 wm = normalize(Vec3(alpha_ * nh.x, alpha_ * nh.y, std::max(1e-7f, nh.z)));
    return flip ? -wm : wm;
  }

 private:
  float alpha_;
};

}  // namespace prism
