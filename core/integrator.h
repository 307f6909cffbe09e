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
  // The renderer hands li_packet this many camera rays at a time (eight of Embree's packets): the
  // more paths in lockstep, the fuller the packets and SIMD lanes their survivors fill, up to where
  // the paths' state outgrows the cache (the box's instructions: 32 paths 2.096G, 64 2.078G, 128
  // 2.095G; docs/PERFORMANCE.md, session 44).
  static constexpr int kPathsInLockstep = 64;
  // li for n camera rays at once, lane k drawing from samplers[k] and reporting to aovs[k]
  // (aovs null: no AOVs); out[k] is what li would return for lane k. The default traces the lanes
  // one after another; integrators that trace them in lockstep share Embree's packet queries
  // between them.
  virtual void li_packet(const Scene& scene, const Ray* camera_rays, Sampler* const* samplers, int n,
                         RayCounters& counters, AovSample* const* aovs, RadianceSample* out) const {
    for (int k = 0; k < n; ++k)
      out[k] = li(scene, camera_rays[k], *samplers[k], counters, aovs ? aovs[k] : nullptr);
  }
};

}  // namespace prism
