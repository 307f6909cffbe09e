// Bsdf: the scattering function at one shading point, in world space, for a fixed outgoing direction.
#pragma once

#include <optional>

#include "core/frame.h"
#include "materials/lambertian.h"

namespace prism {

struct BsdfSample {
  Vec3 wi;
  Rgb f_cos;  // f(wo, wi) |cos theta_i|
  float pdf = 0;
};

class Bsdf {
 public:
  // ns and ng are unit shading and geometric normals (any orientation); wo points away from
  // the surface. Both normals are flipped to wo's side of the geometric surface.
  Bsdf(const Vec3& ns, const Vec3& ng, const Vec3& wo, const Rgb& albedo);

  // f(wo, wi) |cos theta_i| (with the shading normal); zero for wi below the geometric surface,
  // so shading normals never let light through it.
  Rgb eval(const Vec3& wi) const;
  float pdf(const Vec3& wi) const;
  std::optional<BsdfSample> sample(Vec2 u) const;

 private:
  Frame frame_;  // around the oriented shading normal
  Vec3 ng_;      // oriented geometric normal
  Lambertian lobe_;
  bool valid_;   // false when wo grazes the geometric surface exactly
};

}  // namespace prism
