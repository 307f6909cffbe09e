// Lambertian diffuse reflection in the local shading frame (+z is the normal).
#pragma once

#include "core/constants.h"
#include "core/sampling.h"
#include "core/vec3.h"

namespace prism {

struct Lambertian {
  Rgb albedo;

  // f(wo, wi) for wi in the upper hemisphere.
  Rgb f() const { return albedo * kInvPi; }
  // Cosine-weighted direction in the upper hemisphere.
  static Vec3 sample(Vec2 u) { return sample_cosine_hemisphere(u); }
  static float pdf(const Vec3& wi_local) { return cosine_hemisphere_pdf(wi_local.z); }
};

}  // namespace prism
