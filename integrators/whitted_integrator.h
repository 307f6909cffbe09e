// WhittedIntegrator: the classic recursive ray tracer (Whitted 1980): punctual lights with shadow
// rays for the diffuse part, recursive mirror reflection, and Fresnel-weighted splitting into
// reflected and refracted rays at dielectrics, with Beer's law inside volumes.
#pragma once

#include "core/integrator.h"
#include "integrators/medium_stack.h"

namespace prism {

// Every surface is treated as smooth (roughness is ignored: Whitted has no glossy transport);
// area lights contribute only when seen directly or through mirrors and glass.
class WhittedIntegrator final : public Integrator {
 public:
  explicit WhittedIntegrator(int max_depth) : max_depth_(max_depth) {}

  RadianceSample li(const Scene& scene, const Ray& camera_ray, Sampler& sampler, RayCounters& counters,
                    AovSample* aov = nullptr) const override;

 private:
  // `from` is the surface point a secondary ray leaves (its origin is offset off it), null for
  // the camera ray; `alpha` receives coverage and `aov` the AOVs for the camera ray.
  Rgb trace(const Scene& scene, const Ray& ray, const Vec3* from, int depth, const MediumStack& media,
            RayCounters& counters, float* alpha = nullptr, AovSample* aov = nullptr) const;

  int max_depth_;
};

}  // namespace prism
