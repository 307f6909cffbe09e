// Path splitting at the first vertex (PathIntegrator::set_split): the continuations draw a longer
// render's samples, keep every estimate's mean, and lower the error as independent samples of the
// light past the first vertex must.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/renderer.h"
#include "core/sampler_factory.h"
#include "core/scene.h"
#include "furnace_scene.h"
#include "integrators/path_integrator.h"
#include "io/gltf_loader.h"
#include "statistics.h"

namespace prism {
namespace {

constexpr int kNoRoulette = 1 << 20;

// The furnace's closed form with every sampler, two and three continuations (the mean of three is
// no power of two), with and without Russian roulette: the first vertex's light sample, taken by
// one continuation for all, must count as much as without splitting.
TEST(PathSplitting, TheFurnaceKeepsItsRadiance) {
  for (int split : {2, 3}) {
    test::expect_furnace(test::furnace_box(1.0, 0.5), test::furnace_camera(Vec3(0.1f)), 0.5, 5, kNoRoulette,
                         test::furnace_radiance(1.0, 0.5, 5), 0, split);
    test::expect_furnace(test::furnace_box(1.0, 0.8), test::furnace_camera(Vec3(0.0f)), 0.8, 12, 1,
                         test::furnace_radiance(1.0, 0.8, 12), 0, split);
  }
}

// The Cornell box (an area light: next-event estimation and MIS at every vertex) renders the same
// image split as not: over the pixels, whose errors are independent (each pixel draws its own
// scrambles), the mean difference between the two renders is within its standard error.
TEST(PathSplitting, TheCornellBoxIsTheSameImage) {
  Diagnostics diag;
  SceneDesc desc = load_gltf(PRISM_SOURCE_DIR "/scenes/cornell-box/cornell-box.gltf", diag);
  const CameraDesc cam = desc.cameras.at(0);
  const Scene scene(std::move(desc));
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.spp = 64;
  std::vector<float> images[2];
  for (int s = 0; s < 2; ++s) {
    PathIntegrator integrator(settings.max_depth, settings.rr_start_depth);
    integrator.set_split(s == 0 ? 1 : 4);
    settings.seed = uint64_t(10 + s);  // independent noise in the two
    Film film(settings.width, settings.height);
    render(scene, Camera(cam, settings.width, settings.height), integrator, settings, film);
    images[s] = film.resolve_rgba();
  }
  for (int c = 0; c < 3; ++c) {
    test::RunningStats difference, unsplit;
    for (size_t i = size_t(c); i < images[0].size(); i += 4) {
      difference.add(double(images[1][i]) - images[0][i]);
      unsplit.add(images[0][i]);
    }
    std::printf("channel %d: mean %.5f, split minus unsplit %.5f +- %.5f\n", c, unsplit.mean(), difference.mean(),
                difference.standard_error());
    EXPECT_LT(std::abs(difference.mean()), test::kSigmas * difference.standard_error()) << "channel " << c;
  }
}

// With independent samples a camera sample's variance is A + B, A from what it draws up to its
// first vertex's light sample and B from its continuation; K continuations make it A + B / K. The
// RMSE ratio must then lie between 1/sqrt(K) and 1, and below 1 by more than its spread: the
// continuations draw values of their own (in the furnace every bounce adds light, so B > 0).
TEST(PathSplitting, ContinuationsLowerTheErrorAsIndependentSamplesMust) {
  const int size = 40, spp = 8, split = 4;
  const auto [r1, s1] = test::rmse_with_error(test::furnace_errors("independent", spp, size, 3));
  const auto [rk, sk] = test::rmse_with_error(test::furnace_errors("independent", spp, size, 3, split));
  const double ratio = rk / r1;
  const double sigma = ratio * std::hypot(s1 / r1, sk / rk);
  std::printf("RMSE %.5f unsplit, %.5f in %d continuations: ratio %.3f +- %.3f\n", r1, rk, split, ratio, sigma);
  EXPECT_LT(ratio, 1 - test::kSigmas * sigma);
  EXPECT_GT(ratio, 1 / std::sqrt(double(split)) - test::kSigmas * sigma);
  // Sobol's continuations, a longer render's samples, must lower it too.
  const auto [q1, t1] = test::rmse_with_error(test::furnace_errors("sobol", spp, size, 3));
  const auto [qk, tk] = test::rmse_with_error(test::furnace_errors("sobol", spp, size, 3, split));
  std::printf("sobol: RMSE %.5f unsplit, %.5f in %d continuations\n", q1, qk, split);
  EXPECT_LT(qk, q1 - test::kSigmas * std::hypot(t1, tk));
}

}  // namespace
}  // namespace prism
