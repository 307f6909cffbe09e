// PathIntegrator: unidirectional path tracing with next-event estimation, MIS and Russian roulette.
#pragma once

#include "core/integrator.h"
#include "integrators/medium_stack.h"
#include "materials/bsdf.h"

namespace prism {

class PathIntegrator final : public Integrator {
 public:
  // max_depth: bounces (0 = directly visible emission only); Russian roulette starts at
  // bounce rr_start_depth; max_diffuse_depth limits non-delta bounces (-1: no limit of its own);
  // clamp_indirect > 0 scales each sample's indirect light (after two or more scattering events)
  // down to that maximum component, trading bias for fewer fireflies.
  PathIntegrator(int max_depth, int rr_start_depth, int max_diffuse_depth = -1, float clamp_indirect = 0)
      : max_depth_(max_depth),
        rr_start_depth_(rr_start_depth),
        max_diffuse_depth_(max_diffuse_depth),
        clamp_indirect_(clamp_indirect) {}

  RadianceSample li(const Scene& scene, const Ray& camera_ray, Sampler& sampler, RayCounters& counters,
                    AovSample* aov = nullptr) const override;

 private:
  Rgb direct_light(const Scene& scene, const SurfaceHit& hit, const Bsdf& bsdf, const MediumStack& media,
                   const MaterialDesc& material, bool from_front, float u_pick, Vec2 u_point,
                   RayCounters& counters) const;

  int max_depth_;
  int rr_start_depth_;
  int max_diffuse_depth_;
  float clamp_indirect_;
};

}  // namespace prism
