// Radiance at the extremes: emitters from 1e-6 to 1e8, tiny bright emitters, a light reached only
// through a mirror (a high-variance estimate), a black scene and a scene without lights.
#include <gtest/gtest.h>

#include <cmath>

#include "core/camera.h"
#include "core/renderer.h"
#include "core/sampler.h"
#include "core/scene.h"
#include "furnace_scene.h"
#include "integrators/path_integrator.h"
#include "radiance_stats.h"
#include "scene_builders.h"
#include "statistics.h"

namespace prism {
namespace {

constexpr int kNoRoulette = 1 << 20;
constexpr double kAlbedo = 0.5;

// The furnace's radiance is linear in its emission: Le from 1e-6 to 1e8 gives the closed form
// scaled by Le, to the same relative tolerance, with no non-finite sample.
TEST(RadianceExtremes, FurnaceScalesWithEmissionFrom1e6Down1e8Up) {
  for (double le : {1e-6, 1e-2, 1e4, 1e8}) {
    SCOPED_TRACE("Le " + std::to_string(le));
    test::expect_furnace(test::furnace_box(le, kAlbedo), Vec3(0.1f), le, kAlbedo, 4, kNoRoulette);
  }
}

// Estimates of the radiance leaving a diffuse plane at (x, 0, 0) upward, with max depth `depth`.
test::RunningStats plane_radiance(const Scene& scene, float x, int depth, int samples) {
  return test::radiance_stats(scene, PathIntegrator(depth, kNoRoulette), samples, {.seed = 2024},
                              [&](int) { return Ray{Vec3(x, 0.0f, 0.05f), Vec3(0, 0, -1)}; });
}

SceneDesc lit_plane(float radius, float le, const Vec3& centre) {
  SceneDesc desc;
  const int ground = test::add_material(desc, Rgb(float(kAlbedo)));
  test::add_quad(desc, Vec3(-50, -50, 0), Vec3(100, 0, 0), Vec3(0, 100, 0), ground);
  const int light = test::add_material(desc, Rgb(0.0f), Rgb(le));
  test::add_sphere(desc, centre, radius, light);
  return desc;
}

// A sphere emitter of radius r and radiance Le wholly above a diffuse plane, at distance d and
// height h over the shaded point, gives Lo = albedo Le (r/d)^2 (h/d). Radii 1e-4 and 1e-2 with
// Le = 1/r^2 (1e8 and 1e4): the same light, from a speck and from a ball.
TEST(RadianceExtremes, TinyBrightSphereLightsAPlaneLikeItsClosedForm) {
  for (float r : {1e-4f, 1e-2f}) {
    const double le = 1.0 / (double(r) * r);
    const Scene scene(lit_plane(r, float(le), Vec3(0, 0, 1)));
    for (float x : {0.0f, 1.5f}) {
      const test::RunningStats s = plane_radiance(scene, x, 1, 4000);
      const double d2 = double(x) * x + 1.0;
      const double expected = kAlbedo * le * double(r) * r / d2 / std::sqrt(d2);
      EXPECT_NEAR(s.mean(), expected, test::kSigmas * s.standard_error() + 1e-4 * expected) << "r " << r << " x " << x;
    }
  }
}

// The same light seen also through a perfect mirror (metal, base colour 1, roughness 0) at
// height 2: its image at height 3 lights the plane as a second sphere, but only BSDF sampling
// can find it (a mirror is a delta lobe, no light sampling through it), so a few hundred of a
// million paths carry all of that light: the estimate is heavy-tailed, and its mean must still
// match albedo Le r^2 (h/d^3 + h'/d'^3).
TEST(RadianceExtremes, LightFoundOnlyThroughAMirrorStillConvergesToTheClosedForm) {
  const float r = 0.05f, x = 1.5f;
  const double le = 1.0 / (double(r) * r);
  SceneDesc desc = lit_plane(r, float(le), Vec3(0, 0, 1));
  MaterialDesc mirror;
  mirror.base_color = Rgb(1.0f);
  mirror.metallic = 1.0f;
  mirror.roughness = 0.0f;
  desc.materials.push_back(mirror);
  test::add_quad(desc, Vec3(-50, -50, 2), Vec3(0, 100, 0), Vec3(100, 0, 0), int(desc.materials.size()) - 1);
  const Scene scene(std::move(desc));
  // Depth 2: plane -> mirror -> light. Deeper paths would add light the closed form leaves out.
  const test::RunningStats s = plane_radiance(scene, x, 2, 1 << 20);
  auto sphere_term = [&](double h) { return kAlbedo * le * double(r) * r * h / std::pow(double(x) * x + h * h, 1.5); };
  const double expected = sphere_term(1.0) + sphere_term(3.0);
  EXPECT_GT(sphere_term(3.0), 0.2 * expected);  // the mirror's share is not lost in the noise
  EXPECT_NEAR(s.mean(), expected, test::kSigmas * s.standard_error()) << "standard error " << s.standard_error();
}

// Renders a 16x16 image of `desc` from above; returns the image and counts non-finite samples.
std::vector<float> render_from_above(SceneDesc desc, uint64_t& nonfinite) {
  const Scene scene(std::move(desc));
  CameraDesc cam;
  cam.camera_to_world = Transform::look_at(Vec3(0, 0, 3), Vec3(0.0f), Vec3(0, 1, 0));
  RenderSettings settings;
  settings.width = settings.height = 16;
  settings.spp = 4;
  Film film(16, 16);
  nonfinite = render(scene, Camera(cam, 16, 16), PathIntegrator(8, 3), settings, film).nonfinite_samples;
  return film.resolve_rgba();
}

// A black scene (every surface black, a sun shining) and a scene without any light render
// exactly 0 in colour, with full coverage, and no non-finite sample.
TEST(RadianceExtremes, BlackSceneAndSceneWithoutLightsRenderExactZero) {
  for (bool has_sun : {true, false}) {
    SceneDesc desc;
    const int m = test::add_material(desc, Rgb(has_sun ? 0.0f : 0.8f));
    test::add_quad(desc, Vec3(-50, -50, 0), Vec3(100, 0, 0), Vec3(0, 100, 0), m);
    test::add_sphere(desc, Vec3(0, 0, 0.5f), 0.5f, m);
    if (has_sun) {
      PunctualLightDesc sun;
      sun.type = LightType::Directional;
      sun.direction = normalize(Vec3(0.2f, 0.1f, -1.0f));
      sun.intensity = Rgb(5.0f);
      desc.lights.push_back(sun);
    }
    uint64_t nonfinite = 1;
    const std::vector<float> rgba = render_from_above(std::move(desc), nonfinite);
    EXPECT_EQ(nonfinite, 0u);
    for (size_t i = 0; i < rgba.size(); i += 4) {
      ASSERT_EQ(rgba[i], 0.0f) << (has_sun ? "black scene" : "no lights");
      ASSERT_EQ(rgba[i + 1], 0.0f);
      ASSERT_EQ(rgba[i + 2], 0.0f);
      ASSERT_EQ(rgba[i + 3], 1.0f);
    }
  }
}

}  // namespace
}  // namespace prism
