// Direct lighting of a diffuse plane by spherical and rectangular emitters against analytic irradiance.
#include <gtest/gtest.h>

#include <cmath>

#include "core/constants.h"
#include "core/sampler.h"
#include "core/scene.h"
#include "integrators/path_integrator.h"
#include "radiance_stats.h"
#include "scene_builders.h"
#include "statistics.h"

namespace prism {
namespace {

constexpr double kAlbedo = 0.5;

// Mean radiance leaving the plane at (x, y, 0) toward +z, estimated with max depth 1 (direct light).
test::RunningStats estimate(const Scene& scene, float x, float y, int samples) {
  return test::radiance_stats(scene, PathIntegrator(1, 1 << 20), samples, {.seed = 77},
                              [&](int) { return Ray{Vec3(x, y, 0.05f), Vec3(0, 0, -1), 0.0f, 1.0f}; });
}

SceneDesc plane_scene() {
  SceneDesc desc;
  const int ground = test::add_material(desc, Rgb(float(kAlbedo)));
  test::add_quad(desc, Vec3(-50, -50, 0), Vec3(100, 0, 0), Vec3(0, 100, 0), ground);
  return desc;
}

TEST(DirectLighting, SphericalEmitterMatchesAnalyticIrradiance) {
  // A uniformly emitting sphere wholly above the horizon gives E = pi Le (r/d)^2 cos(theta), so the
  // diffuse plane reflects Lo = albedo Le (r/d)^2 (h/d).
  const double le = 10.0, r = 0.1, h = 1.0;
  SceneDesc desc = plane_scene();
  const int light = test::add_material(desc, Rgb(0.0f), Rgb(float(le)));
  test::add_sphere(desc, Vec3(0, 0, float(h)), float(r), light);
  const Scene scene(std::move(desc));
  for (float x : {0.0f, 0.3f, 1.0f, 2.5f}) {
    const test::RunningStats s = estimate(scene, x, 0.0f, 40000);
    const double d = std::sqrt(double(x) * x + h * h);
    const double expected = kAlbedo * le * (r * r) / (d * d) * (h / d);
    EXPECT_NEAR(s.mean(), expected, test::kSigmas * s.standard_error() + 1e-6 * expected) << "x = " << x;
  }
}

// Form factor from a differential area to a parallel rectangle a x b at height 1 whose corner lies
// straight above it (Howell's catalogue, configuration B-3).
double corner_form_factor(double a, double b) {
  const double sa = std::sqrt(1 + a * a), sb = std::sqrt(1 + b * b);
  return (a / sa * std::atan(b / sa) + b / sb * std::atan(a / sb)) / (2.0 * kPi);
}

TEST(DirectLighting, RectangularEmitterMatchesAnalyticIrradiance) {
  // A 2a x 2b rectangle at height h centred above the point: four corner rectangles,
  // E = pi Le F, Lo = albedo Le F. Its triangles are sampled by solid angle from the point (h is
  // under their longest edge); at h = 0.1 they fill 4.5 of the hemisphere's 2 pi steradians.
  for (const double h : {0.8, 0.1}) {
    const double le = 4.0, a = 0.4, b = 0.25;
    SceneDesc desc = plane_scene();
    const int light = test::add_material(desc, Rgb(0.0f), Rgb(float(le)));
    // Corners ordered so the front face (cross(u, v)) points down at the plane.
    test::add_quad(desc, Vec3(float(-a), float(-b), float(h)), Vec3(0, float(2 * b), 0), Vec3(float(2 * a), 0, 0), light);
    const Scene scene(std::move(desc));
    const test::RunningStats s = estimate(scene, 0.0f, 0.0f, 40000);
    const double expected = kAlbedo * le * 4.0 * corner_form_factor(a / h, b / h);
    EXPECT_NEAR(s.mean(), expected, test::kSigmas * s.standard_error() + 1e-6 * expected) << "h = " << h;
  }
}

TEST(DirectLighting, BackOfSingleSidedEmitterIsDark) {
  SceneDesc desc = plane_scene();
  const int light = test::add_material(desc, Rgb(0.0f), Rgb(4.0f));
  // Front face up, away from the plane.
  test::add_quad(desc, Vec3(-0.4f, -0.25f, 0.8f), Vec3(0.8f, 0, 0), Vec3(0, 0.5f, 0), light);
  const Scene scene(std::move(desc));
  const test::RunningStats s = estimate(scene, 0.0f, 0.0f, 2000);
  EXPECT_EQ(s.mean(), 0.0);
}

}  // namespace
}  // namespace prism
