// Thin sheets that light crosses straight on: what a sheet lets through, and that a room behind a
// pane is lit by next-event estimation through it with every mean where it belongs.
#include <gtest/gtest.h>

#include <cmath>

#include "core/constants.h"
#include "core/sampler.h"
#include "furnace_scene.h"
#include "integrators/whitted_integrator.h"
#include "materials/bsdf.h"
#include "materials/fresnel.h"
#include "scene_builders.h"

namespace prism {
namespace {

constexpr float kIor = 1.5f;
constexpr double kAlbedo = 0.5;

// What a smooth thin sheet of index kIor reflects at cosine mu: r at the first face, plus the
// light reflected back and forth inside it, r + t^2 r / (1 - r^2) with t = 1 - r.
double sheet_reflectance(double mu) {
  const double r = fresnel_dielectric(float(mu), kIor);
  return r + (1 - r) * (1 - r) * r / (1 - r * r);
}

// The sheet's reflectance averaged over a cosine-weighted hemisphere, 2 int R(mu) mu dmu
// (midpoint rule): what it sends back of a uniform radiance.
double hemispherical_reflectance() {
  constexpr int kSteps = 200000;
  double sum = 0;
  for (int i = 0; i < kSteps; ++i) {
    const double mu = (i + 0.5) / kSteps;
    sum += sheet_reflectance(mu) * 2 * mu / kSteps;
  }
  return sum;
}

// The furnace camera's replacement: between the floor (y = 0) and the pane (y = 1), looking down.
CameraDesc floor_camera() {
  CameraDesc cam;
  cam.camera_to_world = Transform::look_at(Vec3(0, 0.5f, 0), Vec3(0, 0, 0), Vec3(0, 0, 1));
  cam.yfov = 1.0f;
  return cam;
}

// A white Lambertian floor of albedo kAlbedo under a thin glass pane, both wide enough to be
// infinite planes for a point near the middle (the gap at their edges is 4e-6 of its view).
SceneDesc floor_under_pane() {
  SceneDesc desc;
  test::add_quad(desc, Vec3(-500, 0, -500), Vec3(0, 0, 1000), Vec3(1000, 0, 0),
                 test::add_material(desc, Rgb(float(kAlbedo))));
  test::add_quad(desc, Vec3(-500, 1, -500), Vec3(0, 0, 1000), Vec3(1000, 0, 0),
                 test::add_glass(desc, kIor, Rgb(1.0f), 1.0f, /*thin_walled=*/true));
  return desc;
}

// Light that has bounced between floor and pane: each round trip floor -> pane -> floor takes two
// more scattering events and multiplies by a rho; max_depth d keeps rounds k with 2k + 1 <= d.
double round_trips(double rho, int max_depth) {
  double sum = 0;
  for (int k = 0; 2 * k + 1 <= max_depth; ++k) sum += std::pow(kAlbedo * rho, k);
  return sum;
}

TEST(SheetCrossing, StraightThroughIsWhatSamplingPassesStraightOn) {
  // Over a fine grid of the lobe draw, the straight transmitted samples' weights average to
  // straight_through(); every other surface passes nothing straight.
  SurfaceParams pane;
  pane.base_color = Rgb(0.9f, 0.8f, 0.6f);
  pane.roughness = 0;
  pane.transmission = 1;
  SurfaceParams tinted_metal_sheet = pane;
  tinted_metal_sheet.metallic = 0.3f;
  tinted_metal_sheet.transmission = 0.6f;
  const Vec3 n(0, 0, 1);
  for (const SurfaceParams& p : {pane, tinted_metal_sheet})
    for (const float cos_o : {1.0f, 0.6f, 0.1f}) {
      for (const float side : {1.0f, -1.0f}) {  // a sheet is the same from both faces
        const Vec3 wo(std::sqrt(1 - cos_o * cos_o), 0, side * cos_o);
        const Bsdf bsdf(p, n, n, wo, kIor);
        constexpr int kDraws = 100000;
        double sum[3] = {};
        for (int i = 0; i < kDraws; ++i) {
          const auto s = bsdf.sample((i + 0.5f) / kDraws, Vec2{0.3f, 0.7f});
          if (s && s->delta && s->transmission) {
            EXPECT_NEAR(dot(s->wi, wo), -1.0f, 1e-6f);
            for (int c = 0; c < 3; ++c) sum[c] += double(s->f_cos[c]) / s->pdf / kDraws;
          }
        }
        const Rgb expected = bsdf.straight_through();
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], expected[c], 2e-5) << cos_o << " " << side;
        EXPECT_NEAR(expected[1] / pane.base_color[1], (1 - p.metallic) * p.transmission * (1 - sheet_reflectance(cos_o)),
                    1e-5);
      }
    }
  SurfaceParams rough = pane, volume = pane;
  rough.roughness = 0.3f;
  volume.thin_walled = false;
  for (const SurfaceParams& p : {rough, volume, SurfaceParams{}})
    EXPECT_TRUE(is_black(Bsdf(p, n, n, normalize(Vec3(0.2f, 0, 1)), kIor).straight_through()));
}

// The floor under the pane, lit by a sun of illuminance pi at 30 degrees off vertical.
SceneDesc sunlit_floor_under_pane() {
  SceneDesc desc = floor_under_pane();
  PunctualLightDesc sun;
  sun.type = LightType::Directional;
  sun.direction = normalize(Vec3(-0.5f, -std::sqrt(0.75f), 0));
  sun.intensity = Rgb(float(kPi));
  desc.lights.push_back(sun);
  return desc;
}

TEST(SheetCrossing, SunThroughAPaneLightsTheFloorBelow) {
  // The floor's radiance is a / pi x pi x T(cos) x cos, plus what the pane reflects back of the
  // floor's own light. No path can find a sun by itself: without shadow rays through the pane the
  // floor is black. The Whitted tracer, with no diffuse interreflection, gives the first term.
  const double cos_sun = std::sqrt(0.75);
  const double direct = kAlbedo * (1 - sheet_reflectance(cos_sun)) * cos_sun;
  for (const int depth : {1, 5})
    test::expect_furnace(sunlit_floor_under_pane(), floor_camera(), kAlbedo, depth, 100,
                         direct * round_trips(hemispherical_reflectance(), depth));

  const Scene scene(sunlit_floor_under_pane());
  IndependentSampler sampler(0);
  RayCounters counters;
  const RadianceSample L = WhittedIntegrator(8).li(scene, Ray{Vec3(0, 0.5f, 0), Vec3(0, -1, 0)}, sampler, counters);
  EXPECT_NEAR(L.radiance.y, direct, 1e-5);
}

TEST(SheetCrossing, SkyThroughAPaneKeepsEveryMean) {
  // A uniform sky of radiance 1 above the pane, as an environment and as a wide emitting quad:
  // the floor gets a x (1 - rho) from it, rho the pane's hemispherical reflectance, and the
  // round trips. Next-event estimation through the pane and paths crossing it share that light
  // by MIS: counted twice or left out, the mean moves. At depth 1 the paths find the sky only
  // by crossing the pane after their last scattering event.
  const double rho = hemispherical_reflectance();
  SceneDesc sky = floor_under_pane();
  sky.environment.present = true;
  sky.environment.color = Rgb(1.0f);
  SceneDesc lamp = floor_under_pane();
  test::add_quad(lamp, Vec3(-500, 2, -500), Vec3(1000, 0, 0), Vec3(0, 0, 1000),
                 test::add_material(lamp, Rgb(0.0f), Rgb(1.0f)));
  for (const int depth : {1, 5}) {
    const double expected = kAlbedo * (1 - rho) * round_trips(rho, depth);
    test::expect_furnace(sky, floor_camera(), kAlbedo, depth, 100, expected);
    test::expect_furnace(lamp, floor_camera(), kAlbedo, depth, 100, expected);
  }
}

}  // namespace
}  // namespace prism
