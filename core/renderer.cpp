#include "core/renderer.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <vector>

#include "core/parallel_ranges.h"
#include "core/sample_schedule.h"
#include "core/sampler_factory.h"

namespace prism {

RenderStats render(const Scene& scene, const Camera& world_camera, const Integrator& integrator,
                   const RenderSettings& settings, Film& film, RenderProgress* progress,
                   const PassObserver& after_pass) {
  const Camera camera = world_camera.relative_to(scene.origin());  // rays in the scene's coordinates
  const int width = film.width(), height = film.height();
  // Film pixel (x, y) is image pixel (x + x0, y + y0): a crop renders the pixels a full render would.
  const int x_offset = settings.crop.empty() ? 0 : settings.crop.x0, y_offset = settings.crop.empty() ? 0 : settings.crop.y0;
  const bool path_aovs = film.aovs().needs_path_data();
  const int tile = std::max(1, settings.tile_size);
  const int tiles_x = (width + tile - 1) / tile, tiles_y = (height + tile - 1) / tile;
  make_sampler(settings.sampler, settings.seed);  // reject an unknown name before any work

  RenderStats stats;
  std::mutex stats_mutex;
  const auto start = std::chrono::steady_clock::now();
  std::vector<uint32_t> target;  // each pixel's sample count at the end of the current pass
  std::atomic<uint64_t> samples{0};

  auto stopping = [&] { return progress && progress->stop_requested(); };

  // A tile's samples go to the integrator in packets of consecutive (pixel, sample) pairs, in the
  // order a one-by-one loop would take them, and reach the film in that order.
  constexpr int kLanes = Integrator::kPathsInLockstep;
  auto render_tile = [&](int tile_index) {
    const int x0 = (tile_index % tiles_x) * tile, y0 = (tile_index / tiles_x) * tile;
    const int x1 = std::min(x0 + tile, width), y1 = std::min(y0 + tile, height);
    const std::vector<std::unique_ptr<Sampler>> lane_samplers = make_lane_samplers(settings.sampler, settings.seed, kLanes);
    Sampler* samplers[kLanes];
    for (int k = 0; k < kLanes; ++k) samplers[k] = lane_samplers[size_t(k)].get();
    RayCounters counters;
    uint64_t nonfinite = 0;
    // Counted once per tile: shared counters updated per packet bounce their cache line between
    // the cores.
    uint64_t tile_samples = 0;
    AovSample aov[kLanes];  // filled only when the film has AOVs
    AovSample* aovs[kLanes];
    for (int k = 0; k < kLanes; ++k) aovs[k] = &aov[k];
    Ray rays[kLanes];
    RadianceSample L[kLanes];
    int lane_x[kLanes], lane_y[kLanes];
    int lanes = 0;
    auto flush = [&] {
      if (lanes == 0) return;
      if (path_aovs)
        for (int k = 0; k < lanes; ++k) aov[k] = AovSample{};
      integrator.li_packet(scene, rays, samplers, lanes, counters, path_aovs ? aovs : nullptr, L);
      for (int k = 0; k < lanes; ++k) {
        const int x = lane_x[k], y = lane_y[k];
        // A non-finite estimate counts as a black sample, so counts stay sample indices.
        const bool finite = is_finite(L[k].radiance) && std::isfinite(L[k].alpha);
        film.add_sample(x, y, finite ? L[k].radiance : Rgb(0.0f), finite ? L[k].alpha : 0.0f);
        if (path_aovs) {
          AovSample& a = aov[k];
          if (!finite) a.emission = a.direct = a.indirect = Rgb(0.0f);
          const float depth = a.hit ? camera.planar_depth(a.position) : kBackgroundDepth;
          if (a.hit) a.position = a.position + scene.origin();  // back to world coordinates
          film.add_aov_sample(x, y, a, depth);
        }
        nonfinite += !finite;
      }
      tile_samples += uint64_t(lanes);
      lanes = 0;
    };
    for (int y = y0; y < y1 && !stopping(); ++y) {
      for (int x = x0; x < x1 && !stopping(); ++x) {
        const uint64_t end = target[size_t(y) * width + x];
        const int px = x + x_offset, py = y + y_offset;
        // film.sample_count does not move until the packet reaches the film: count from there.
        for (uint64_t s = film.sample_count(x, y); s < end; ++s) {
          if (lanes == kLanes) {
            flush();
            if (stopping()) break;
          }
          Sampler& sampler = *samplers[lanes];
          sampler.start_pixel_sample(px, py, settings.first_sample + s);
          const Vec2 jitter = sampler.next_2d();  // box filter: uniform in the pixel
          rays[lanes] = camera.generate_ray(float(px) + jitter.x, float(py) + jitter.y);
          lane_x[lanes] = x;
          lane_y[lanes] = y;
          ++lanes;
        }
      }
    }
    if (!stopping()) flush();
    if (progress) progress->samples_done.fetch_add(tile_samples, std::memory_order_relaxed);
    samples.fetch_add(tile_samples, std::memory_order_relaxed);
    std::lock_guard lock(stats_mutex);
    stats.rays += counters;
    stats.nonfinite_samples += nonfinite;
  };

  // ThreadSanitizer builds hand the tiles to std::threads, settings.threads of them (parallel_ranges.h).
  auto run_pass = [&] {
    parallel_ranges(tiles_x * tiles_y, settings.threads, [&](int first, int end) {
      for (int t = first; t < end; ++t) render_tile(t);
    });
  };
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };

  SampleSchedule schedule(settings, width, height);
  if (schedule.uses_halves()) film.track_halves();
  std::optional<tbb::task_arena> arena;
  if (settings.threads > 0) arena.emplace(settings.threads);
  if (!settings.crop.empty() && (settings.crop.width() != width || settings.crop.height() != height))
    throw std::invalid_argument("the film does not match the crop window");

  // What the budgets reached so far: spp spread, estimated error, time.
  auto summarize = [&] {
    stats.stopped = stopping();
    stats.samples = samples;
    stats.seconds = elapsed();
    schedule.update_floor(film);
    const Film::SampleCounts counts = film.sample_counts();
    stats.spp_min = counts.min;
    stats.spp_max = counts.max;
    uint64_t converged = 0;
    const std::vector<double> errors = schedule.estimated_errors(film);
    for (double e : errors) converged += settings.noise_target > 0 && e <= settings.noise_target;
    const double pixels = double(width) * height;
    stats.spp_mean = double(counts.total) / pixels;  // a resumed film's samples count too
    stats.relative_error = schedule.image_error(film, errors);
    stats.converged_fraction = double(converged) / pixels;
  };

  bool first = true;
  while (!stopping() && schedule.next_pass(film, elapsed(), samples.load(), target)) {
    if (!first && after_pass) {
      summarize();
      stats.passes = schedule.passes() - 1;  // the pass just planned has not run
      after_pass(film, stats);
    }
    first = false;
    if (progress)
      progress->samples_total.store(std::max(schedule.expected_samples(), samples.load()), std::memory_order_relaxed);
    if (arena) arena->execute(run_pass);
    else run_pass();
  }
  summarize();
  stats.passes = schedule.passes() - (stats.stopped ? 0 : 1);  // the last call found nothing left to do
  return stats;
}

}  // namespace prism
