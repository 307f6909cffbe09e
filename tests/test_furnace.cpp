// Furnace tests: closed emitting diffuse enclosures have the analytic radiance Le (1 - a^(d+1)) / (1 - a).
#include <gtest/gtest.h>

#include <cmath>

#include "core/camera.h"
#include "core/renderer.h"
#include "core/scene.h"
#include "integrators/path_integrator.h"
#include "furnace_scene.h"
#include "scene_builders.h"
#include "statistics.h"

namespace prism {
namespace {

using test::expect_furnace;
using test::furnace_box;
using test::furnace_radiance;

SceneDesc furnace_sphere(double le, double albedo) {
  SceneDesc desc;
  const int m = test::add_material(desc, Rgb(float(albedo)), Rgb(float(le)), /*double_sided=*/true);
  test::add_sphere(desc, Vec3(0.5f, -0.2f, 0.1f), 2.0f, m);
  return desc;
}

constexpr int kNoRoulette = 1 << 20;

TEST(Furnace, BoxDepthZeroSeesOnlyEmission) { expect_furnace(furnace_box(1.0, 0.5), Vec3(0.1f), 1.0, 0.5, 0, kNoRoulette); }

TEST(Furnace, BoxMatchesAnalyticRadianceAtEachDepth) {
  for (int depth : {1, 2, 5}) expect_furnace(furnace_box(1.0, 0.5), Vec3(0.1f), 1.0, 0.5, depth, kNoRoulette);
}

TEST(Furnace, BoxHighAlbedoDeepPaths) { expect_furnace(furnace_box(0.5, 0.8), Vec3(0.0f), 0.5, 0.8, 12, kNoRoulette); }

TEST(Furnace, BoxRussianRouletteKeepsTheMean) {
  expect_furnace(furnace_box(1.0, 0.8), Vec3(0.0f), 1.0, 0.8, 12, 1);
  expect_furnace(furnace_box(1.0, 0.5), Vec3(0.0f), 1.0, 0.5, 6, 2);
}

TEST(Furnace, SphereInteriorMatchesAnalyticRadiance) {
  expect_furnace(furnace_sphere(1.0, 0.5), Vec3(0.4f, 0.1f, -0.3f), 1.0, 0.5, 4, kNoRoulette);
  expect_furnace(furnace_sphere(2.0, 0.7), Vec3(0.4f, 0.1f, -0.3f), 2.0, 0.7, 8, 1);
}

// Clamping indirect light removes light after two or more scattering events: with a vanishing
// clamp the furnace keeps exactly its direct part, Le (1 + a); with a huge one nothing changes.
TEST(Furnace, ClampIndirectKeepsOnlyWhatItShould) {
  const Scene scene(furnace_box(1.0, 0.5));
  const int depth = 4;
  for (const auto& [clamp, expected] : {std::pair{1e-20f, 1.5}, std::pair{1e30f, furnace_radiance(1.0, 0.5, depth)}}) {
    RenderSettings settings;
    settings.width = settings.height = 16;
    settings.spp = 16;
    settings.max_depth = depth;
    const PathIntegrator integrator(depth, kNoRoulette, -1, clamp);
    Film film(16, 16);
    render(scene, Camera(test::furnace_camera(), 16, 16), integrator, settings, film);
    test::RunningStats pixels;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) {
        float rgba[4];
        film.mean(x, y, rgba);
        pixels.add(rgba[0]);
      }
    EXPECT_NEAR(pixels.mean(), expected, test::kSigmas * pixels.standard_error() + 1e-5) << "clamp " << clamp;
  }
}

}  // namespace
}  // namespace prism
