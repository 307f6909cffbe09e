// PathIntegrator: unidirectional path tracing with next-event estimation, MIS and Russian roulette.
#pragma once

#include "core/integrator.h"

namespace prism {

class PathIntegrator final : public Integrator {
 public:
  // max_depth: bounces (0 = directly visible emission only); Russian roulette starts at
  // bounce rr_start_depth.
  PathIntegrator(int max_depth, int rr_start_depth) : max_depth_(max_depth), rr_start_depth_(rr_start_depth) {}

  RadianceSample li(const Scene& scene, const Ray& camera_ray, Sampler& sampler,
                    RayCounters& counters) const override;

 private:
  int max_depth_;
  int rr_start_depth_;
};

}  // namespace prism
