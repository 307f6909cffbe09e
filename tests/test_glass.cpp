// Glass in whole renders: Beer-Lambert through a slab, a coloured cube against its closed form
// with internal reflections, and glass of IOR 1 that must be invisible.
#include <gtest/gtest.h>

#include <cmath>

#include "core/camera.h"
#include "core/renderer.h"
#include "core/sampler.h"
#include "core/scene.h"
#include "integrators/path_integrator.h"
#include "materials/fresnel.h"
#include "scene_builders.h"
#include "statistics.h"

namespace prism {
namespace {

constexpr int kNoRoulette = 1 << 20;

// Radiance along the -z axis from (x, y, 2) with many independent samples.
test::RunningStats trace_axis(const Scene& scene, int samples, float x = 0.0f, float y = 0.0f) {
  const PathIntegrator integrator(200, kNoRoulette);
  IndependentSampler sampler(5);
  RayCounters counters;
  test::RunningStats stats[3];
  for (int i = 0; i < samples; ++i) {
    sampler.start_pixel_sample(0, 0, uint64_t(i));
    const RadianceSample L = integrator.li(scene, Ray{Vec3(x, y, 2), Vec3(0, 0, -1)}, sampler, counters);
    EXPECT_TRUE(is_finite(L.radiance));
    for (int c = 0; c < 3; ++c) stats[c].add(L.radiance[c]);
  }
  return stats[0];
}

// A white emitter facing +z below everything, radiance le.
void add_backlight(SceneDesc& desc, float le) {
  const int light = test::add_material(desc, Rgb(0.0f), Rgb(le));
  test::add_quad(desc, Vec3(-50, -50, -3), Vec3(100, 0, 0), Vec3(0, 100, 0), light);
}

TEST(BeerLambert, IndexOneSlabTransmitsExactlyExpMinusSigmaD) {
  for (float thickness : {1e-3f, 0.25f, 1.0f})
    for (float colour : {0.0f, 0.05f, 0.5f, 1.0f}) {
      const float distance = 0.4f;
      SceneDesc desc;
      add_backlight(desc, 2.0f);
      const int glass = test::add_glass(desc, 1.0f, Rgb(colour, 1.0f, 0.5f), distance);
      test::add_box(desc, Vec3(-5, -5, -thickness), Vec3(5, 5, 0), glass);
      const Scene scene(std::move(desc));
      const test::RunningStats s = trace_axis(scene, 200);
      const double sigma = colour > 0 ? -std::log(double(colour)) / distance : INFINITY;
      const double expected = 2.0 * std::exp(-sigma * thickness);
      EXPECT_NEAR(s.mean(), expected, 1e-5 * 2.0) << "thickness " << thickness << " colour " << colour;
      EXPECT_EQ(s.variance(), 0.0);  // every path takes the same straight line
    }
}

TEST(BeerLambert, ColouredGlassCubeMatchesClosedFormAlongItsAxis) {
  // At normal incidence each face reflects R = ((n-1)/(n+1))^2 and the radiance scaling cancels
  // between entering and leaving; summing the light bounced back and forth inside gives
  // L = Le (1-R)^2 e^{-sigma d} / (1 - R^2 e^{-2 sigma d}).
  const double n = 1.5, d = 0.8, le = 3.0;
  const double R = ((n - 1) / (n + 1)) * ((n - 1) / (n + 1));
  for (double colour : {0.2, 0.7, 1.0}) {
    SceneDesc desc;
    add_backlight(desc, float(le));
    const int glass = test::add_glass(desc, float(n), Rgb(float(colour)), 0.5f);
    test::add_box(desc, Vec3(-1, -1, float(-d)), Vec3(1, 1, 0), glass);
    const Scene scene(std::move(desc));
    const test::RunningStats s = trace_axis(scene, 100000);
    const double sigma = -std::log(colour) / 0.5;
    const double a = std::exp(-sigma * d);
    const double expected = le * (1 - R) * (1 - R) * a / (1 - R * R * a * a);
    EXPECT_NEAR(s.mean(), expected, test::kSigmas * s.standard_error() + 1e-6 * expected) << "colour " << colour;
  }
}

TEST(Glass, IndexOneIsInvisible) {
  // A diffuse floor lit by a ceiling emitter; a glass sphere of IOR 1 (and a thin sheet) hangs in
  // between. The image must not change beyond noise.
  auto make_scene = [](bool with_glass) {
    SceneDesc desc;
    const int floor = test::add_material(desc, Rgb(0.6f));
    test::add_quad(desc, Vec3(-2, -2, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), floor);
    const int light = test::add_material(desc, Rgb(0.0f), Rgb(5.0f));
    test::add_quad(desc, Vec3(-0.5f, -0.5f, 2), Vec3(0, 1, 0), Vec3(1, 0, 0), light);
    if (with_glass) {
      test::add_sphere(desc, Vec3(0.1f, 0, 0.8f), 0.5f, test::add_glass(desc, 1.0f));
      test::add_quad(desc, Vec3(-1, -1, 1.5f), Vec3(2, 0, 0), Vec3(0, 2, 0), test::add_glass(desc, 1.0f, Rgb(1.0f), 1.0f, true));
    }
    return desc;
  };
  CameraDesc cam;
  cam.camera_to_world = Transform::look_at(Vec3(0, -3, 2.5f), Vec3(0, 0, 0.5f), Vec3(0, 0, 1));
  cam.yfov = 0.9f;
  RenderSettings settings;
  settings.width = settings.height = 24;
  settings.spp = 64;
  settings.sampler = "independent";  // the seed-swap test models pixel errors as independent noise
  const PathIntegrator integrator(settings.max_depth, settings.rr_start_depth);
  // Two seeds of each scene: differences between seeds measure the noise pixel by pixel.
  std::vector<float> images[2][2];
  for (int g = 0; g < 2; ++g) {
    const Scene scene(make_scene(g == 1));
    for (int seed = 0; seed < 2; ++seed) {
      settings.seed = uint64_t(seed);
      Film film(settings.width, settings.height);
      render(scene, Camera(cam, settings.width, settings.height), integrator, settings, film);
      images[g][seed] = film.resolve_rgba();
    }
  }
  // Under "invisible", with-vs-without differences are as large as seed-vs-seed ones.
  test::SeedSwapTest swap;
  for (size_t i = 0; i < images[0][0].size(); i += 4)
    swap.add(images[1][0][i], images[1][1][i], images[0][0][i], images[0][1][i]);
  ASSERT_TRUE(swap.has_noise());
  EXPECT_LT(std::log(swap.ratio()), test::kSigmas * swap.log_ratio_sigma());
}

}  // namespace
}  // namespace prism
