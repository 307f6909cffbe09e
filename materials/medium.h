// Absorbing media (Beer-Lambert): the interior of a closed transmissive mesh with KHR_materials_volume.
#pragma once

#include <cmath>
#include <limits>

#include "core/scene_desc.h"

namespace prism {

// Absorption coefficient per channel, sigma_a = -ln(attenuationColor) / attenuationDistance
// (KHR_materials_volume). A colour channel of 0 absorbs completely (+inf); an infinite distance
// or a channel of 1 absorbs nothing (0).
inline Rgb absorption_coefficient(const MaterialDesc& m) {
  Rgb sigma;
  for (int c = 0; c < 3; ++c) {
    const float colour = std::clamp(m.attenuation_color[c], 0.0f, 1.0f);
    const float d = m.attenuation_distance;
    if (colour >= 1.0f || !(d < std::numeric_limits<float>::infinity())) sigma[c] = 0.0f;
    else if (colour <= 0.0f || d <= 0.0f) sigma[c] = std::numeric_limits<float>::infinity();
    else sigma[c] = -std::log(colour) / d;
  }
  return sigma;
}

// Transmittance exp(-sigma d) over a path length d >= 0, exact and never NaN (0 x inf is 1 here:
// no distance, no absorption).
inline Rgb beer_lambert(const Rgb& sigma, float d) {
  Rgb t(1.0f);
  if (!(d > 0)) return t;
  for (int c = 0; c < 3; ++c)
    if (sigma[c] > 0) t[c] = std::exp(-sigma[c] * d);
  return t;
}

}  // namespace prism
