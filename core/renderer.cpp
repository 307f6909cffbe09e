#include "core/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>

namespace prism {

RenderStats render(const Scene& scene, const Camera& camera, const Integrator& integrator,
                   const RenderSettings& settings, Film& film, RenderProgress* progress) {
  const int width = film.width(), height = film.height();
  const int tile = std::max(1, settings.tile_size);
  const int tiles_x = (width + tile - 1) / tile, tiles_y = (height + tile - 1) / tile;
  const auto spp = static_cast<uint64_t>(std::max(0, settings.spp));
  if (progress) progress->samples_total = uint64_t(width) * height * spp;

  RenderStats stats;
  std::mutex stats_mutex;
  const auto start = std::chrono::steady_clock::now();

  auto render_tile = [&](int tile_index) {
    const int x0 = (tile_index % tiles_x) * tile, y0 = (tile_index / tiles_x) * tile;
    const int x1 = std::min(x0 + tile, width), y1 = std::min(y0 + tile, height);
    IndependentSampler sampler(settings.seed);
    RayCounters counters;
    uint64_t nonfinite = 0;
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        for (uint64_t s = 0; s < spp; ++s) {
          sampler.start_pixel_sample(x, y, s);
          const Vec2 jitter = sampler.next_2d();  // box filter: uniform in the pixel
          const Ray ray = camera.generate_ray(float(x) + jitter.x, float(y) + jitter.y);
          const RadianceSample L = integrator.li(scene, ray, sampler, counters);
          if (is_finite(L.radiance) && std::isfinite(L.alpha)) {
            film.add_sample(x, y, L.radiance, L.alpha);
          } else {
            ++nonfinite;
          }
        }
        if (progress) progress->samples_done.fetch_add(spp, std::memory_order_relaxed);
      }
    }
    std::lock_guard lock(stats_mutex);
    stats.rays += counters;
    stats.nonfinite_samples += nonfinite;
  };

  auto run = [&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y, 1),
                      [&](const tbb::blocked_range<int>& r) {
                        for (int t = r.begin(); t < r.end(); ++t) render_tile(t);
                      });
  };
  if (settings.threads > 0) {
    tbb::task_arena arena(settings.threads);
    arena.execute(run);
  } else {
    run();
  }
  stats.samples = uint64_t(width) * height * spp;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace prism
