// A furnace for tests: a closed, uniformly emitting diffuse box whose radiance is known exactly.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "core/renderer.h"
#include "core/sampler_factory.h"
#include "core/scene.h"
#include "core/scene_desc.h"
#include "integrators/path_integrator.h"
#include "scene_builders.h"
#include "statistics.h"

namespace prism::test {

// Every bounce k adds a^k Le, up to max depth d: Le (1 - a^(d+1)) / (1 - a).
inline double furnace_radiance(double le, double albedo, int max_depth) {
  return le * (1.0 - std::pow(albedo, max_depth + 1)) / (1.0 - albedo);
}

// The box spans about 2 x scale, centred near `offset`.
inline SceneDesc furnace_box(double le, double albedo, float scale = 1.0f, const Vec3& offset = Vec3(0.0f)) {
  SceneDesc desc;
  const int m = add_material(desc, Rgb(float(albedo)), Rgb(float(le)));
  add_inward_box(desc, Vec3(-1.0f, -0.7f, -1.3f) * scale + offset, Vec3(1.2f, 0.9f, 1.0f) * scale + offset, m);
  return desc;
}

// A wide-angle camera inside the furnace, looking at a corner.
inline CameraDesc furnace_camera(const Vec3& eye = Vec3(0.1f)) {
  CameraDesc cam;
  cam.camera_to_world = Transform::look_at(eye, eye + Vec3(0.3f, 0.2f, -1.0f), Vec3(0, 1, 0));
  cam.yfov = 1.6f;
  return cam;
}

// The furnace box (emission 1, albedo 0.5) seen by furnace_camera, rendered with `settings`.
struct FurnaceRender {
  RenderStats stats;
  Film film;
};
inline FurnaceRender render_furnace(const RenderSettings& settings) {
  const Scene scene(furnace_box(1.0, 0.5));
  FurnaceRender out{{}, Film(settings.width, settings.height)};
  const PathIntegrator integrator(settings.max_depth, settings.rr_start_depth);
  out.stats =
      render(scene, Camera(furnace_camera(), settings.width, settings.height), integrator, settings, out.film);
  return out;
}

// The RMS over pixels of the green channel's relative error against the known radiance `truth` of a
// render to a noise target, printed with what the render reached; infinite (and a failure) when a
// pixel is not finite.
inline double noise_target_render_error(const FurnaceRender& r, double truth, const std::string& sampler,
                                        double target) {
  double sq = 0;
  for (int y = 0; y < r.film.height(); ++y)
    for (int x = 0; x < r.film.width(); ++x) {
      float rgba[4];
      r.film.mean(x, y, rgba);
      if (!std::isfinite(rgba[1])) {
        ADD_FAILURE() << "pixel " << x << ", " << y << " is not finite";
        return INFINITY;
      }
      sq += (rgba[1] - truth) * (rgba[1] - truth) / (truth * truth);
    }
  const double rms = std::sqrt(sq / (double(r.film.width()) * r.film.height()));
  std::printf("%s, target %.3f: real relative error %.4f, estimated %.4f, spp %llu-%llu (mean %.1f), %d passes\n",
              sampler.c_str(), target, rms, r.stats.relative_error, (unsigned long long)r.stats.spp_min,
              (unsigned long long)r.stats.spp_max, r.stats.spp_mean, r.stats.passes);
  return rms;
}

// Renders a small image from inside the enclosure with each sampler; each pixel mean is an
// independent estimate (pixels are scrambled independently), so the image mean's standard error
// is the spread of pixel means over sqrt(pixels). caster_share and split are the path tracer's.
inline void expect_furnace(SceneDesc desc, const CameraDesc& cam, double albedo, int max_depth, int rr_start,
                           double expected, float caster_share = 0, int split = 1) {
  const Scene scene(std::move(desc));
  for (const std::string& sampler : sampler_names()) {
    RenderSettings settings;
    settings.width = settings.height = 24;
    settings.spp = 32;
    settings.max_depth = max_depth;
    settings.rr_start_depth = rr_start;
    settings.seed = 1234;
    settings.sampler = sampler;
    Film film(settings.width, settings.height);
    PathIntegrator integrator(settings.max_depth, settings.rr_start_depth, -1, 0, caster_share);
    integrator.set_split(split);
    const RenderStats stats = render(scene, Camera(cam, settings.width, settings.height), integrator, settings, film);
    EXPECT_EQ(stats.nonfinite_samples, 0u);
    for (int c = 0; c < 3; ++c) {
      RunningStats pixels;
      for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
          float rgba[4];
          film.mean(x, y, rgba);
          pixels.add(rgba[c]);
        }
      // The float rounding of a sum of ~d terms bounds how exact even a noiseless estimate is.
      const double tolerance = kSigmas * pixels.standard_error() + 1e-5 * expected;
      EXPECT_NEAR(pixels.mean(), expected, tolerance) << sampler << " sampler, channel " << c << ", albedo "
                                                      << albedo << ", depth " << max_depth << ", rr from " << rr_start
                                                      << ", caster share " << caster_share << ", split " << split;
    }
  }
}

// The same, from furnace_camera(eye), against the closed form.
inline void expect_furnace(SceneDesc desc, const Vec3& eye, double le, double albedo, int max_depth, int rr_start) {
  expect_furnace(std::move(desc), furnace_camera(eye), albedo, max_depth, rr_start,
                 furnace_radiance(le, albedo, max_depth));
}

// Renders the furnace box (emission 1, albedo 0.5, depth 4, no roulette); returns each pixel's
// error against the exact radiance (green channel). split: the path tracer's.
inline std::vector<double> furnace_errors(const std::string& sampler, int spp, int size, uint64_t seed, int split = 1) {
  const int depth = 4;
  const Scene scene(furnace_box(1.0, 0.5));
  RenderSettings settings;
  settings.width = settings.height = size;
  settings.spp = spp;
  settings.max_depth = depth;
  settings.rr_start_depth = 1 << 20;
  settings.seed = seed;
  settings.sampler = sampler;
  Film film(size, size);
  PathIntegrator integrator(settings.max_depth, settings.rr_start_depth);
  integrator.set_split(split);
  render(scene, Camera(furnace_camera(), size, size), integrator, settings, film);
  const double truth = furnace_radiance(1.0, 0.5, depth);
  std::vector<double> errors;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      float rgba[4];
      film.mean(x, y, rgba);
      errors.push_back(rgba[1] - truth);
    }
  return errors;
}

// Root mean square error over pixels, and its standard error (from the spread of squared errors).
inline std::pair<double, double> rmse_with_error(const std::vector<double>& errors) {
  RunningStats sq;
  for (double e : errors) sq.add(e * e);
  const double rmse = std::sqrt(sq.mean());
  return {rmse, 0.5 * rmse * sq.standard_error() / sq.mean()};  // d sqrt(m) = dm / (2 sqrt(m))
}

}  // namespace prism::test
