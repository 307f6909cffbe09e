// Thin sheets that light crosses straight on: what a sheet lets through, and that a room behind a
// pane is lit by next-event estimation through it with every mean where it belongs.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/constants.h"
#include "core/pcg32.h"
#include "core/sampler.h"
#include "furnace_scene.h"
#include "integrators/sheet_crossing.h"
#include "integrators/whitted_integrator.h"
#include "materials/bsdf.h"
#include "materials/fresnel.h"
#include "materials/material_eval.h"
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
        const Rgb expected = Bsdf::straight_through(p, n, n, wo, kIor);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], expected[c], 2e-5) << cos_o << " " << side;
        EXPECT_NEAR(expected[1] / pane.base_color[1], (1 - p.metallic) * p.transmission * (1 - sheet_reflectance(cos_o)),
                    1e-5);
      }
    }
  SurfaceParams rough = pane, volume = pane;
  rough.roughness = 0.3f;
  volume.thin_walled = false;
  for (const SurfaceParams& p : {rough, volume, SurfaceParams{}})
    EXPECT_TRUE(is_black(Bsdf::straight_through(p, n, n, normalize(Vec3(0.2f, 0, 1)), kIor)));
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

TEST(SheetCrossing, OcclusionLooksPastSheetsAndNothingElse) {
  // A floor, an opaque box and a roof beside panes: one baked into the world, one mesh placed twice
  // (instanced), one on a tinted pane. Shadow segments and rays to the sky between them: where
  // the query that looks past sheets says blocked, walking the hits one by one finds no light;
  // where it says clear and crossed no sheet, all of it; where it crossed one, the closest hit
  // is a sheet and the walk decides.
  SceneDesc desc;
  const int white = test::add_material(desc, Rgb(0.5f));
  const int pane = test::add_glass(desc, kIor, Rgb(1.0f), 1.0f, /*thin_walled=*/true);
  test::add_quad(desc, Vec3(-4, 0, -4), Vec3(0, 0, 8), Vec3(8, 0, 0), white);
  test::add_box(desc, Vec3(-0.5f, 0, -0.5f), Vec3(0.5f, 1, 0.5f), white);
  test::add_quad(desc, Vec3(-4, 2.5f, -4), Vec3(2, 0, 0), Vec3(0, 0, 8), white);  // a roof over one side
  test::add_quad(desc, Vec3(-2, 2, -2), Vec3(0, 0, 2), Vec3(2, 0, 0), pane);
  const int twice = test::add_quad(desc, Vec3(0, 0, 0), Vec3(0, 0, 2), Vec3(2, 0, 0), pane,
                                   Transform::translate(Vec3(0, 2, -2)));
  desc.instances.push_back({"second placement", twice, Transform::translate(Vec3(0, 3, 0))});
  const Scene scene(std::move(desc));
  ASSERT_TRUE(scene.sees_every_sheet());

  IndependentSampler sampler(7);
  sampler.start_pixel_sample(0, 0, 0);
  constexpr int kRays = 4000;
  std::vector<Ray> rays;
  for (int i = 0; i < kRays; ++i) {
    const Vec3 o(8 * sampler.next_1d() - 4, 0.01f + 0.98f * sampler.next_1d(), 8 * sampler.next_1d() - 4);
    if (i % 2 == 0) {  // toward a point above the panes: a shadow segment
      const Vec3 target(8 * sampler.next_1d() - 4, 4, 8 * sampler.next_1d() - 4);
      rays.emplace_back(o, target - o, 0.0f, 1.0f);
    } else {  // toward the sky
      const Vec3 w = normalize(Vec3(sampler.next_1d() - 0.5f, sampler.next_1d(), sampler.next_1d() - 0.5f));
      rays.emplace_back(o, w);
    }
  }
  std::vector<char> blocked(kRays);
  std::vector<Scene::SheetsCrossed> crossed(kRays);
  scene.occluded_past_sheets(rays.data(), kRays, reinterpret_cast<bool*>(blocked.data()), crossed.data());
  // What the integrators ask: the query, and the crossings' factors from the hits it met.
  std::vector<float> iors(kRays, 1.0f);
  std::vector<Rgb> through(kRays);
  RayCounters counters;
  shadow_transmittance(scene, rays.data(), iors.data(), kRays, through.data(), counters);
  int counts[3] = {0, 0, 0};  // blocked, clear, crossed
  for (int i = 0; i < kRays; ++i) {
    const Rgb walked = transmittance_through_sheets(scene, rays[i], 1.0f, counters);
    EXPECT_TRUE(through[i].x == walked.x && through[i].y == walked.y && through[i].z == walked.z) << "ray " << i;
    SurfaceHit hit;
    const bool found = scene.intersect(rays[i], hit);
    if (blocked[i]) {
      ++counts[0];
      EXPECT_TRUE(is_black(walked)) << "ray " << i;
      EXPECT_EQ(crossed[i].count, 0) << "ray " << i;
    } else if (crossed[i].count == 0) {
      ++counts[1];
      EXPECT_FALSE(found) << "ray " << i;
      EXPECT_EQ(walked.y, 1.0f) << "ray " << i;
    } else {
      ++counts[2];
      ASSERT_TRUE(found) << "ray " << i;
      EXPECT_TRUE(scene.desc().material(hit.material).is_thin_sheet()) << "ray " << i;
      EXPECT_GT(walked.y, 0.0f) << "ray " << i;  // the panes are clear and nothing opaque is behind
    }
  }
  for (const int c : counts)  // every case met often
    EXPECT_GT(c, kRays / 20) << "blocked " << counts[0] << ", clear " << counts[1] << ", crossed " << counts[2];
  // Rays that cross the instanced pane twice placed (x > 0, z in (-2, 0)) and the baked one: one
  // crossing each.
  for (const Vec3 o : {Vec3(1, 1.5f, -1), Vec3(-1, 1.5f, -1)}) {
    const Ray up(o, Vec3(0, 1, 0));
    bool b = true;
    Scene::SheetsCrossed c;
    scene.occluded_past_sheets(&up, 1, &b, &c);
    EXPECT_FALSE(b);
    EXPECT_EQ(c.count, 1);
  }
}

TEST(SheetCrossing, APaneMetOnItsDiagonalIsCrossedOnce) {
  // A ray along the edge the pane's two triangles share may be reported on both, at one distance:
  // that is one crossing, as a walk (whose next segment starts past the plane) counts it.
  SceneDesc desc;
  test::add_quad(desc, Vec3(-4, 1, -4), Vec3(0, 0, 8), Vec3(8, 0, 0),
                 test::add_glass(desc, kIor, Rgb(1.0f), 1.0f, /*thin_walled=*/true));
  const Scene scene(std::move(desc));
  const float straight = float(1 - sheet_reflectance(1.0));
  for (const float s : {-3.0f, -1.25f, 0.0f, 0.5f, 2.75f}) {
    for (const Vec3 o : {Vec3(s, 0.5f, s), Vec3(s, 0.5f, -s)}) {  // the diagonal is one of the two
      const Ray up(o, Vec3(0, 1, 0), 0.0f, 2.0f);
      bool blocked = true;
      Scene::SheetsCrossed crossed;
      scene.occluded_past_sheets(&up, 1, &blocked, &crossed);
      EXPECT_FALSE(blocked);
      EXPECT_EQ(crossed.count, 1) << "at " << o.x << ", " << o.z;
      const float ior = 1;
      Rgb through;
      RayCounters counters;
      shadow_transmittance(scene, &up, &ior, 1, &through, counters);
      EXPECT_NEAR(through.y, straight, 1e-6f) << "at " << o.x << ", " << o.z;
    }
  }
}

TEST(SheetCrossing, ABlendSurfaceBehindPanesIsDecidedOnce) {
  // Shadow segments up through clear panes (from y = 1), then a surface of BLEND alpha 0.5 (y = 2):
  // each passes with probability 0.5 and then carries the panes' straight transmittance. The
  // occlusion query decides the BLEND surface as it looks past the panes, and their factors come
  // from the hits it met: a walk past the panes would decide the BLEND surface a second time, by
  // a segment of its own, and let a quarter through. More panes than a walk crosses stop the ray.
  for (const int panes : {1, kMaxSheetCrossings, kMaxSheetCrossings + 1}) {
    SceneDesc desc;
    const int glass = test::add_glass(desc, kIor, Rgb(1.0f), 1.0f, /*thin_walled=*/true);
    for (int i = 0; i < panes; ++i)
      test::add_quad(desc, Vec3(-4, 1 + 0.05f * float(i), -4), Vec3(0, 0, 8), Vec3(8, 0, 0), glass);
    const int leaf = test::add_material(desc, Rgb(0.5f));
    desc.materials[size_t(leaf)].base_alpha = 0.5f;
    desc.materials[size_t(leaf)].alpha_mode = MaterialDesc::AlphaMode::Blend;
    test::add_quad(desc, Vec3(-4, 2, -4), Vec3(0, 0, 8), Vec3(8, 0, 0), leaf);
    const Scene scene(std::move(desc), &material_alpha);
    ASSERT_TRUE(scene.sees_every_sheet());

    constexpr int kRays = 4000;
    Pcg32 rng(3, 11);
    std::vector<Ray> rays;
    for (int i = 0; i < kRays; ++i) {
      const Vec3 o(4 * rng.next_float() - 2, 0.5f, 4 * rng.next_float() - 2);
      rays.emplace_back(o, Vec3(0, 2.5f, 0), 0.0f, 1.0f);
    }
    const std::vector<float> iors(kRays, 1.0f);
    std::vector<Rgb> through(kRays);
    RayCounters counters;
    shadow_transmittance(scene, rays.data(), iors.data(), kRays, through.data(), counters);
    // The query counts every pane once, more than it keeps included.
    bool blocked = true;
    Scene::SheetsCrossed crossed;
    for (int i = 0; blocked && i < kRays; ++i) scene.occluded_past_sheets(&rays[size_t(i)], 1, &blocked, &crossed);
    EXPECT_EQ(crossed.count, panes);
    if (panes > kMaxSheetCrossings) {
      for (int i = 0; i < kRays; ++i) EXPECT_TRUE(is_black(through[i])) << panes << " panes, ray " << i;
      continue;
    }
    const float straight = std::pow(float(1 - sheet_reflectance(1.0)), float(panes));  // at normal incidence
    int passed = 0;
    for (int i = 0; i < kRays; ++i) {
      if (is_black(through[i])) continue;
      ++passed;
      EXPECT_NEAR(through[i].y, straight, 1e-4f) << panes << " panes, ray " << i;
    }
    // Binomial: 0.5 with standard deviation sqrt(0.25 / kRays) = 0.0079; four of them.
    EXPECT_NEAR(double(passed) / kRays, 0.5, 4 * std::sqrt(0.25 / kRays)) << panes << " panes";
  }
}

TEST(SheetCrossing, ASheetSphereIsNotSeenPastByOcclusion) {
  // The spheres' intersection code runs no filters, so occlusion cannot look past a sheet sphere:
  // the scene says so and the integrators walk every shadow ray instead.
  SceneDesc desc;
  test::add_sphere(desc, Vec3(0, 0, 0), 1, test::add_glass(desc, kIor, Rgb(1.0f), 1.0f, /*thin_walled=*/true));
  EXPECT_FALSE(Scene(std::move(desc)).sees_every_sheet());
}

}  // namespace
}  // namespace prism
