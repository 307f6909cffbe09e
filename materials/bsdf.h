// Bsdf: the glTF 2.0 metallic-roughness BSDF at one shading point (Appendix B, with
// KHR_materials_transmission and _ior), in world space for a fixed outgoing direction.
#pragma once

#include <algorithm>
#include <optional>

#include "core/frame.h"
#include "materials/conductor_bxdf.h"
#include "materials/dielectric_bxdf.h"
#include "materials/lambertian.h"
#include "materials/surface_params.h"

namespace prism {

struct BsdfSample {
  Vec3 wi;
  Rgb f_cos;  // f(wo, wi) |cos theta_i| (for a delta lobe: the lobe's weight x pdf)
  float pdf = 0;
  bool delta = false;
  bool transmission = false;  // wi crosses the surface
  float eta = 1;              // n_t / n_i when crossing a volume boundary
};

// f = metallic x metal + (1 - metallic) x [ transmission x dielectric(R + T)
//                                          + (1 - transmission) x (coat R + (1 - F(wo)) x diffuse) ]
// Lobes are sampled in proportion to their estimated albedo at wo; non-delta samples are weighted
// by the whole mixture (one-sample MIS over lobes).
class Bsdf {
 public:
  // ns, ng: unit shading and geometric normals, ng on the front (outside) face; wo points away
  // from the surface; eta = n_back / n_front at this interface. Opaque and thin-walled surfaces
  // are two-sided (mirrored to wo's side); volume boundaries are not.
  Bsdf(const SurfaceParams& params, const Vec3& ns, const Vec3& ng, const Vec3& wo, float eta);

  // f |cos theta_i| and the density of sample() choosing wi, non-delta lobes only, from one change
  // of frame: next-event estimation needs both.
  struct Value {
    Rgb f_cos;
    float pdf = 0;
  };
  Value evaluate(const Vec3& wi) const;
  Rgb eval(const Vec3& wi) const { return evaluate(wi).f_cos; }
  float pdf(const Vec3& wi) const { return evaluate(wi).pdf; }
  std::optional<BsdfSample> sample(float u_lobe, Vec2 u) const;
  // The unit normal the BSDF's cosines are taken about (the shading normal, perhaps bent toward wo).
  const Vec3& normal() const { return frame_.n; }
  // True when every lobe with weight is a delta lobe: next-event estimation cannot help.
  bool is_delta() const { return delta_only_; }
  // Whether the mixture at a point with these parameters and eta is the Lambertian lobe alone: no
  // metal, no transmission, and a specular layer that reflects nothing (no index step, or no
  // weight). SIMD kernels make that lobe's frame themselves (integrators/lane_lambertian_lobe.h).
  static bool lambertian_only(const SurfaceParams& params, float eta) {
    return lambertian_only(params.metallic, params.transmission, params.specular, eta);
  }
  // The same, from the three parameters it reads.
  static bool lambertian_only(float metallic, float transmission, float specular, float eta) {
    const float m = std::clamp(metallic, 0.0f, 1.0f), t = std::clamp(transmission, 0.0f, 1.0f);
    return m == 0 && t == 0 && (eta == 1.0f || !(specular > 0));
  }
  // Whether the mixture at a point with these parameters and eta is glTF's opaque metallic-roughness
  // model with rough lobes: GGX metal (weight metallic) and glTF's default dielectric, a GGX layer
  // (its exact Fresnel curve, no KHR_materials_specular remapping) over the Lambertian lobe; no
  // transmission, no delta lobe. SIMD kernels evaluate and sample it themselves
  // (integrators/lane_coated_lobe.h).
  static bool coated_only(const SurfaceParams& params, float eta) {
    const float t = std::clamp(params.transmission, 0.0f, 1.0f);
    return t == 0 && eta != 1.0f && params.specular == 1.0f && params.specular_color == Rgb(1.0f) &&
           params.roughness * params.roughness >= GgxDistribution::kSmoothAlpha;
  }
  // True when no lobe transmits: every direction it scatters to stays on wo's side.
  bool reflects_only() const { return weight_[kDielectric] == 0; }
  // What passes straight through a smooth thin-walled sheet along -wo: the weight the sample()s of
  // Bsdf(params, ns, ng, wo, eta) that go straight through carry, times how often it draws them. A
  // shadow ray may cross the sheet with this factor instead of stopping at it. Zero for every other
  // surface. Made without the mixture's other lobes, which it does not need.
  static Rgb straight_through(const SurfaceParams& params, const Vec3& ns, const Vec3& ng, const Vec3& wo, float eta);
  // normal() of a Bsdf whose parameters transmit nothing, made without it.
  static Vec3 reflecting_normal(const Vec3& ns, const Vec3& ng, const Vec3& wo) { return facing(ns, ng, wo, false).n; }

 private:
  enum Lobe { kMetal, kDielectric, kCoat, kDiffuse, kLobes };

  // The side of the surface wo is on, and the normal the lobes' cosines are taken about there.
  struct Facing {
    Vec3 ng;  // the geometric normal, mirrored to wo's side on two-sided surfaces
    Vec3 n;   // the shading normal likewise, perhaps bent toward wo
    float wo_dot_ng = 0;
    bool valid = false;  // wo is not in the surface's plane
  };
  static Facing facing(const Vec3& ns, const Vec3& ng, const Vec3& wo, bool volume_boundary);
  // The dielectric lobe as the mixture builds it.
  static DielectricBxdf dielectric_lobe(const SurfaceParams& p, float eta, float alpha);

  // The lobe's f (unweighted) and its own density of choosing wi.
  BxdfValue lobe_value(int lobe, const Vec3& wi) const;
  bool lobe_is_delta(int lobe) const;
  bool consistent(const Vec3& wi_world, const Vec3& wi_local) const;

  Frame frame_;
  Vec3 ng_;
  Vec3 wo_;           // local
  float wo_dot_ng_;   // which side of the surface wo is on
  int only_lobe_ = -1;  // the single non-delta lobe that can be picked, if there is just one
  float weight_[kLobes] = {};
  float pick_[kLobes] = {};
  // Built only when the mixture is more than the Lambertian lobe alone (lambertian_ false).
  std::optional<ConductorBxdf> metal_;
  std::optional<DielectricBxdf> dielectric_, coat_;
  Lambertian diffuse_;
  bool valid_ = true;
  bool lambertian_ = false;  // the Lambertian lobe alone: sample() skips the mixture
  bool delta_only_ = false;
};

}  // namespace prism
