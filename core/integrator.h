// Integrator: estimates the radiance arriving along a camera ray (implemented in integrators/).
#pragma once

#include "core/aov.h"
#include "core/ray.h"
#include "core/ray_counters.h"
#include "core/sampler.h"
#include "core/scene.h"

namespace prism {

struct RadianceSample {
  Rgb radiance;
  float alpha = 0;  // 1 when the camera ray hit a surface, else 0 (coverage for compositing)
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  // Must be thread-safe: called concurrently for different pixels. With `aov` non-null it also
  // reports the path's first hit and its light split by kind (see AovSample).
  virtual RadianceSample li(const Scene& scene, const Ray& camera_ray, Sampler& sampler, RayCounters& counters,
                            AovSample* aov = nullptr) const = 0;
};

}  // namespace prism
