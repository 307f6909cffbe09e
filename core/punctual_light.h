// Punctual lights (KHR_lights_punctual): what reaches a point from a point, spot or directional
// light, and each light's power for choosing among lights.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/constants.h"
#include "core/scene_desc.h"

namespace prism {

struct PunctualIncidence {
  Vec3 wi;        // unit direction from the point toward the light
  float distance;  // to the light; +inf for directional lights
  Rgb irradiance;  // at a surface facing the light: I / d^2 x falloff (lux), or E for directional
};

// The KHR_lights_punctual recommended range window: the inverse-square law, smoothly forced to
// zero at `range` by max(min(1 - (d / range)^4, 1), 0).
inline float range_window(float distance, float range) {
  if (!(range > 0)) return 1.0f;
  const float r = distance / range;
  return std::clamp(1.0f - (r * r) * (r * r), 0.0f, 1.0f);
}

// The KHR_lights_punctual spot falloff: a smoothstep-free square of a linear ramp between the
// outer and inner cone cosines.
inline float spot_falloff(const PunctualLightDesc& l, float cos_angle) {
  const float scale = 1.0f / std::max(0.001f, l.cos_inner - l.cos_outer);
  const float t = std::clamp((cos_angle - l.cos_outer) * scale, 0.0f, 1.0f);
  return t * t;
}

inline PunctualIncidence punctual_incidence(const PunctualLightDesc& l, const Vec3& p) {
  PunctualIncidence out;
  if (l.type == LightType::Directional) {
    out.wi = -l.direction;
    out.distance = std::numeric_limits<float>::infinity();
    out.irradiance = l.intensity;
    return out;
  }
  const Vec3 d = l.position - p;
  const float dist2 = length_squared(d);
  out.distance = std::sqrt(dist2);
  if (!(out.distance > 0)) {
    out.wi = Vec3(0, 0, 1);
    out.irradiance = Rgb(0.0f);
    return out;
  }
  out.wi = d / out.distance;
  float scale = range_window(out.distance, l.range) / dist2;
  if (l.type == LightType::Spot) scale *= spot_falloff(l, dot(-out.wi, l.direction));
  out.irradiance = l.intensity * scale;
  return out;
}

// Emitted power (luminance-weighted) for light selection; directional lights deliver their
// irradiance over a disc the size of the scene (radius scene_radius).
inline double punctual_power(const PunctualLightDesc& l, float scene_radius) {
  const double i = std::max(0.0f, luminance(l.intensity));
  switch (l.type) {
    case LightType::Point: return 4.0 * kPi * i;
    case LightType::Spot: return kTwoPi * (1.0 - 0.5 * (double(l.cos_inner) + l.cos_outer)) * i;
    default: return kPi * double(scene_radius) * scene_radius * i;
  }
}

}  // namespace prism
