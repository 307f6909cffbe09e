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
  std::atomic<uint64_t> samples_total{0};  // an estimate that may change between passes under a budget
  // Set (e.g. by a signal handler) to stop: tiles in flight stop at their next pixel, and every
  // pixel keeps the samples it has, so the film stays valid and resumable.
  std::atomic<bool> stop{false};
};

struct RenderStats {
  RayCounters rays;
  uint64_t samples = 0;             // camera paths traced
  uint64_t nonfinite_samples = 0;   // NaN or Inf estimates, counted as black samples
  double seconds = 0;
  int passes = 0;                   // progressive passes (1 for a fixed spp)
  uint64_t spp_min = 0, spp_max = 0;
  double spp_mean = 0;
  double relative_error = 0;        // root mean square over pixels of the estimated relative error
  double converged_fraction = 0;    // pixels that met the noise target (adaptive renders)
  bool stopped = false;             // RenderProgress::stop ended the render early
};

// Renders `film` to the budgets of `settings`: settings.spp samples per pixel, or progressive
// passes under a time budget or noise target (see SampleSchedule). Each sample's random numbers
// are a function of (pixel, sample index, dimension, seed), and each pixel's samples are summed in
// index order by one thread, so the image is identical for any thread count or tile size, and a
// progressive render equals a fixed-spp render of the counts it reached. The film covers
// settings.crop (the whole image when empty) and may hold samples already (a resumed render):
// each pixel continues from its count. Film AOVs are filled when the film has any.
RenderStats render(const Scene& scene, const Camera& camera, const Integrator& integrator,
                   const RenderSettings& settings, Film& film, RenderProgress* progress = nullptr);

}  // namespace prism
