// Renderer: renders image tiles in parallel on oneTBB; bits depend only on scene, settings and seed.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

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
  // Set (e.g. by a signal handler) to stop: tiles in flight stop before their next sample, and
  // every pixel keeps the samples it has, so the film stays valid and resumable.
  std::atomic<bool> stop{false};
  const std::atomic<bool>* also_stop = nullptr;  // another flag that stops it when set (a batch's)

  bool stop_requested() const {
    return stop.load(std::memory_order_relaxed) || (also_stop && also_stop->load(std::memory_order_relaxed));
  }
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

// Sees the film and what the budgets reached between two passes of a render (for checkpoints).
using PassObserver = std::function<void(const Film&, const RenderStats&)>;

// Renders `film` to the budgets of `settings`: settings.spp samples per pixel, or progressive
// passes under a time budget or noise target (see SampleSchedule). Each sample's random numbers
// are a function of (pixel, sample index, dimension, seed), and each pixel's samples are summed in
// index order by one thread, so the image is identical for any thread count or tile size, and a
// progressive render equals a fixed-spp render of the counts it reached. The film covers
// settings.crop (the whole image when empty) and may hold samples already (a resumed render):
// each pixel continues from its count, and reaches the bits an uninterrupted render would. Film
// AOVs are filled when the film has any. `after_pass` is called between passes; with
// settings.pass_seconds even a fixed-spp render runs in passes of about that length.
RenderStats render(const Scene& scene, const Camera& camera, const Integrator& integrator,
                   const RenderSettings& settings, Film& film, RenderProgress* progress = nullptr,
                   const PassObserver& after_pass = {});

}  // namespace prism
