// Renderer: renders image tiles in parallel on oneTBB; bits depend only on scene, settings and seed.
#pragma once

#include <atomic>
#include <cstdint>

#include "core/camera.h"
#include "core/film.h"
#include "core/integrator.h"
#include "core/ray_counters.h"
#include "core/render_settings.h"
#include "core/scene.h"

namespace prism {

// Progress counters another thread may read while a render runs.
struct RenderProgress {
  std::atomic<uint64_t> samples_done{0};
  uint64_t samples_total = 0;
};

struct RenderStats {
  RayCounters rays;
  uint64_t samples = 0;             // camera paths traced
  uint64_t nonfinite_samples = 0;   // NaN or Inf estimates, dropped and counted
  double seconds = 0;
};

// Renders settings.spp samples for every pixel of `film`. Each sample's random numbers are a
// function of (pixel, sample index, dimension, seed), and each pixel's samples are summed in
// index order by one thread, so the image is identical for any thread count or tile size.
RenderStats render(const Scene& scene, const Camera& camera, const Integrator& integrator,
                   const RenderSettings& settings, Film& film, RenderProgress* progress = nullptr);

}  // namespace prism
