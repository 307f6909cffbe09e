// BxdfSample: a sampled incident direction with its value and density, in a BxDF's local frame.
#pragma once

#include "core/vec3.h"

namespace prism {

// f(wo, wi) and the density of sample() choosing wi, from one pass over what they share (the
// half vector, Fresnel, the normal distribution and wo's masking).
struct BxdfValue {
  Rgb f;
  float pdf = 0;
};

struct BxdfSample {
  Vec3 wi;
  Rgb f;          // f(wo, wi); for a delta lobe, the value that makes f |cos| / pdf the lobe's weight
  float pdf = 0;  // solid-angle density, or the discrete probability for a delta lobe
  bool delta = false;
  bool transmission = false;  // wi is on the other side of the surface
  float eta = 1;  // for transmission through a volume boundary: n_t / n_i along wi
};

}  // namespace prism
