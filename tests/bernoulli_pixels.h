// A film whose every sample is 1 with a fixed probability, else 0: runs of zeros that a pixel's
// own variance cannot see, for the sample schedules' tests.
#pragma once

#include <cstdint>
#include <vector>

#include "core/film.h"
#include "core/pcg32.h"
#include "core/sample_schedule.h"

namespace prism::test {

// Runs `schedule` to its end on `film`, each sample of pixel i drawn from PCG32 stream i: 1 (all
// channels) with probability `hit`, else 0. Returns the samples taken. The schedule is told that
// each sample took `seconds_per_sample` (a clock for time budgets that does not depend on the
// machine), or that the render has taken 1 s when that is 0.
inline uint64_t render_bernoulli_pixels(SampleSchedule& schedule, Film& film, double hit,
                                        double seconds_per_sample = 0) {
  const int width = film.width(), height = film.height();
  std::vector<Pcg32> streams;
  for (int i = 0; i < width * height; ++i) streams.emplace_back(uint64_t(i), 77);
  std::vector<uint32_t> target;
  uint64_t samples = 0;
  while (schedule.next_pass(film, seconds_per_sample > 0 ? double(samples) * seconds_per_sample : 1.0, samples, target))
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        for (uint64_t n = film.sample_count(x, y); n < target[size_t(y) * size_t(width) + size_t(x)]; ++n, ++samples)
          film.add_sample(x, y, Rgb(streams[size_t(y) * size_t(width) + size_t(x)].next_float() < hit ? 1.0f : 0.0f), 1);
  return samples;
}

}  // namespace prism::test
