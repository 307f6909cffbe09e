// Statistics of an integrator's radiance estimates along given rays, for tests with closed forms.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "core/integrator.h"
#include "core/sampler.h"
#include "core/scene.h"
#include "statistics.h"

namespace prism::test {

// Which estimates radiance_stats draws: sample i of pixel (x, y) of an independent sampler with
// `seed`, reading colour channel `channel`.
struct EstimateSource {
  uint64_t seed = 0;
  int x = 0, y = 0;
  int channel = 0;
};

// `samples` estimates of `integrator` along ray_at(i) for i = 0..samples-1; each must be finite.
template <class RayAt>
RunningStats radiance_stats(const Scene& scene, const Integrator& integrator, int samples, const EstimateSource& source,
                            RayAt ray_at) {
  IndependentSampler sampler(source.seed);
  RayCounters counters;
  RunningStats stats;
  for (int i = 0; i < samples; ++i) {
    const Ray ray = ray_at(i);
    sampler.start_pixel_sample(source.x, source.y, uint64_t(i));
    const float L = integrator.li(scene, ray, sampler, counters).radiance[source.channel];
    EXPECT_TRUE(std::isfinite(L)) << "sample " << i;
    stats.add(L);
  }
  return stats;
}

}  // namespace prism::test
