// Integrator: estimates the radiance arriving along a camera ray (implemented in integrators/).
#pragma once

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
  // Must be thread-safe: called concurrently for different pixels.
  virtual RadianceSample li(const Scene& scene, const Ray& camera_ray, Sampler& sampler,
                            RayCounters& counters) const = 0;
};

}  // namespace prism
