// Scale at the extremes: the same scenes scaled by 1e-4 to 1e6, and moved 1e5 from the origin,
// give the same furnace radiance and slab transmittance, no shadow acne and no light leaks; light
// samples are the same from 1e-15 to 1e18.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "core/emitters.h"
#include "core/pcg32.h"
#include "core/render_origin.h"
#include "core/renderer.h"
#include "core/sampler.h"
#include "core/scene.h"
#include "furnace_scene.h"
#include "integrators/path_integrator.h"
#include "integrators/whitted_integrator.h"
#include "lit_plane.h"
#include "scene_builders.h"
#include "statistics.h"

namespace prism {
namespace {

using test::kNoRoulette;
using test::render_view;
using test::kFar;
using test::kScales;
using test::placements;

void expect_furnace_at(float s, const Vec3& offset) {
  SCOPED_TRACE("scale " + std::to_string(s) + " offset " + std::to_string(offset.x));
  test::expect_furnace(test::furnace_box(1.0, 0.5, s, offset), Vec3(0.05f * s) + offset, 1.0, 0.5, 4, kNoRoulette);
}

TEST(ScaleExtremes, FurnaceRadianceIsTheSameAtEveryScale) {
  for (float s : kScales) expect_furnace_at(s, Vec3(0.0f));
}

// Before scenes were moved to a render origin (core/render_origin.h) this read 1.893 (-2.3%):
// rays slipped out through the box's edges, spawned from hit points that rounded onto the plane
// of the face across the edge.
TEST(ScaleExtremes, FurnaceRadianceHoldsFarFromTheOrigin) { expect_furnace_at(1.0f, kFar); }

// A plane lit by a sun 60 degrees from its normal and seen at a grazing 75 degrees (lit_plane.h):
// direct light from a delta light alone, so every pixel must be exactly albedo / pi x E cos 60; a
// self-shadowed pixel (acne) would be black.
TEST(ScaleExtremes, LitPlaneHasNoAcne) {
  const double expected = test::sunlit_radiance(0.5);
  for (const auto& [s, offset] : placements()) {
    const test::PixelCheck c = test::check_pixels(test::view_lit_plane(test::lit_plane(s, offset), s, offset), expected, expected);
    EXPECT_EQ(c.covered, 32 * 32) << "scale " << s;
    EXPECT_EQ(c.outside, 0) << "scale " << s << " offset " << offset.x;
  }
}

// A closed box (12 triangles) with the camera inside looking into a corner, a sun and a bright
// emitter outside: any light inside leaked through an edge or a corner.
void expect_no_leaks(float s, const Vec3& offset) {
  {
    SceneDesc desc;
    const int wall = test::add_material(desc, Rgb(0.8f));
    test::add_inward_box(desc, Vec3(-1, -1, -1) * s + offset, Vec3(1, 1, 1) * s + offset, wall);
    const int light = test::add_material(desc, Rgb(0.0f), Rgb(1e4f), /*double_sided=*/true);
    test::add_quad(desc, Vec3(-3, -3, 2) * s + offset, Vec3(6, 0, 0) * s, Vec3(0, 6, 0) * s, light);
    PunctualLightDesc sun;
    sun.type = LightType::Directional;
    sun.direction = normalize(Vec3(0.3f, 0.5f, -1.0f));
    sun.intensity = Rgb(1e4f);
    desc.lights.push_back(sun);
    const Film film = render_view(std::move(desc), Vec3(-0.5f) * s + offset, Vec3(1.0f) * s + offset, 8, 32, 16);
    const std::vector<float> rgba = film.resolve_rgba();
    double brightest = 0;
    for (size_t i = 0; i < rgba.size(); i += 4)
      brightest = std::max({brightest, double(rgba[i]), double(rgba[i + 1]), double(rgba[i + 2])});
    EXPECT_EQ(brightest, 0.0) << "scale " << s << " offset " << offset.x;
  }
}

TEST(ScaleExtremes, NoLightLeaksIntoAClosedBox) {
  for (float s : kScales) expect_no_leaks(s, Vec3(0.0f));
}

// Before the render origin, shadow rays from hits rounded onto the neighbouring face's plane let
// the outside light in here.
TEST(ScaleExtremes, NoLightLeaksIntoAClosedBoxFarFromTheOrigin) { expect_no_leaks(1.0f, kFar); }

// A room centred on the origin, and the same room with its camera and light moved by kFar (as a
// glTF node translation does: transforms compose in double). Every coordinate is a multiple of
// 1/8, so the move is exact and the scene moved back to its centre is the same scene: the image
// must be the same bit for bit. Without the render origin its hit points would sit on a 2^-7 grid.
TEST(ScaleExtremes, TranslatedSceneRendersTheSameImageBitForBit) {
  SceneDesc room;
  const int wall = test::add_material(room, Rgb(0.6f, 0.5f, 0.4f));
  test::add_inward_box(room, Vec3(-2.0f), Vec3(2.0f), wall);
  const int lamp = test::add_material(room, Rgb(0.0f), Rgb(5.0f));
  test::add_quad(room, Vec3(-0.5f, -0.5f, 1.875f), Vec3(1, 0, 0), Vec3(0, 1, 0), lamp);
  test::add_sphere(room, Vec3(0.25f, 0.5f, -1.5f), 0.5f, wall);
  PunctualLightDesc bulb;
  bulb.type = LightType::Point;
  bulb.position = Vec3(-1.0f, 1.0f, 1.0f);
  bulb.intensity = Rgb(2.0f);
  room.lights.push_back(bulb);
  CameraDesc cam;
  cam.camera_to_world = Transform::look_at(Vec3(1.5f, -1.5f, 0.5f), Vec3(0.0f), Vec3(0, 0, 1));
  cam.yfov = 1.0f;

  SceneDesc far_room = room;
  move_origin(far_room, -kFar);  // everything moves by +kFar
  CameraDesc far_cam = cam;
  far_cam.camera_to_world = Transform::translate(kFar) * cam.camera_to_world;

  auto image = [](SceneDesc desc, const CameraDesc& camera) {
    const Scene scene(std::move(desc));
    RenderSettings settings;
    settings.width = settings.height = 24;
    settings.spp = 8;
    settings.max_depth = 6;
    Film film(24, 24);
    render(scene, Camera(camera, 24, 24), PathIntegrator(6, 3), settings, film);
    return std::pair(scene.origin(), film.resolve_rgba());
  };
  const auto [near_origin, near_image] = image(room, cam);
  const auto [far_origin, far_image] = image(far_room, far_cam);
  EXPECT_EQ(near_origin, Vec3(0.0f));
  EXPECT_EQ(far_origin, kFar);
  double brightest = 0;
  for (float v : near_image) brightest = std::max(brightest, double(v));
  EXPECT_GT(brightest, 0.1);  // the room is lit: the comparison is not of two black images
  EXPECT_EQ(near_image, far_image);
}

// Radiance along -z through a slab of index 1 (no refraction, no reflection: one deterministic
// path) that absorbs with attenuation distance 0.4 x scale: exp(-sigma d) at every scale, with both
// integrators. Far from the origin the slab is tried twice: alone (the scene moves to a render
// origin) and with a speck at the mirror position, which keeps the scene where it is so the ray
// offsets really are 1e5's; the surface points there are only known to a float spacing, so the
// thickness is, to 2 spacings per face.
TEST(ScaleExtremes, GlassSlabTransmitsTheSameAtEveryScale) {
  const float thickness = 0.25f, colour = 0.3f, le = 2.0f;
  const double expected = le * std::exp(std::log(double(colour)) / 0.4 * thickness);
  const PathIntegrator path(16, kNoRoulette);
  const WhittedIntegrator whitted(16);
  for (const auto& [s, offset] : placements()) {
    for (bool keep_in_place : {false, true}) {
      if (keep_in_place && offset == Vec3(0.0f)) continue;
      SceneDesc desc;
      const int light = test::add_material(desc, Rgb(0.0f), Rgb(le));
      test::add_quad(desc, Vec3(-50, -50, -3) * s + offset, Vec3(100, 0, 0) * s, Vec3(0, 100, 0) * s, light);
      const int glass = test::add_glass(desc, 1.0f, Rgb(colour), 0.4f * s);
      test::add_box(desc, Vec3(-5, -5, -thickness) * s + offset, Vec3(5, 5, 0) * s + offset, glass);
      if (keep_in_place) test::add_sphere(desc, -offset, 1.0f, light);
      const float spacing = std::nextafter(offset.x, INFINITY) - offset.x;  // 0 at the origin
      const double tolerance = expected * (1e-4 + std::log(1.0 / colour) / (0.4 * s) * 4.0 * spacing);
      const Scene scene(std::move(desc));
      EXPECT_EQ(scene.origin() == Vec3(0.0f), keep_in_place || offset == Vec3(0.0f));
      for (const Integrator* integrator : {static_cast<const Integrator*>(&path), static_cast<const Integrator*>(&whitted)}) {
        IndependentSampler sampler(3);
        RayCounters counters;
        for (int i = 0; i < 16; ++i) {
          sampler.start_pixel_sample(0, 0, uint64_t(i));
          const Vec3 from = Vec3(0.01f * i, -0.02f * i, 2.0f) * s + offset - scene.origin();
          const RadianceSample L = integrator->li(scene, Ray{from, Vec3(0, 0, -1)}, sampler, counters);
          EXPECT_NEAR(L.radiance.x, expected, tolerance) << (integrator == &path ? "path" : "whitted") << ", scale "
                                                         << s << " offset " << offset.x << " kept " << keep_in_place;
        }
      }
    }
  }
}

// Light sampling has no scale of its own: scaled with the scene, a quad light's samples land on
// the same points (in units of the scale) with the same solid-angle density, from 1e-15 to 1e18,
// both where it is sampled by solid angle (near its plane) and by area (far). The spherical
// construction once divided by the product of three distances, which overflows a float at ~1e12
// and underflows at ~1e-12, so near lights silently fell back to the noisier area sampling there.
TEST(ScaleExtremes, LightSamplesAreTheSameAtEveryScale) {
  auto light_scene = [](float s) {
    SceneDesc scene;
    const int light = test::add_material(scene, Rgb(0.0f), Rgb(1.0f));
    test::add_quad(scene, Vec3(-0.5f, -0.25f, 1.0f) * s, Vec3(0, 0.5f, 0) * s, Vec3(1.0f, 0, 0) * s, light);  // faces -z
    return scene;
  };
  const SceneDesc unit_scene = light_scene(1.0f);
  // Near: 0.05 under the light's plane, by solid angle; far: 3 under it, by area.
  // The receiving surface faces the light, tilted so the tree's cosine bound is not trivial.
  const Vec3 n = normalize(Vec3(0.3f, 0.2f, 1.0f));
  for (const LightSampling how : {LightSampling::Tree, LightSampling::Power})
  for (const Vec3 ref : {Vec3(0.2f, 0.1f, 0.95f), Vec3(0.2f, 0.1f, -2.0f)}) {
    const Emitters unit(unit_scene, how);
    for (const float s : {1e-15f, 1e-9f, 1e-4f, 1e4f, 1e9f, 1e15f, 1e18f}) {
      SCOPED_TRACE(::testing::Message() << "ref z " << ref.z << " scale " << s << " tree " << (how == LightSampling::Tree));
      const SceneDesc scaled_scene = light_scene(s);
      const Emitters scaled(scaled_scene, how);
      Pcg32 rng(7, 8);
      for (int i = 0; i < 256; ++i) {
        const float u_pick = rng.next_float();
        const Vec2 u{rng.next_float(), rng.next_float()};
        const EmitterSample expected = unit.sample(ref, n, u_pick, u);
        const EmitterSample got = scaled.sample(ref * s, n, u_pick, u);
        ASSERT_GT(expected.pdf, 0.0f);
        ASSERT_NEAR(got.pdf, expected.pdf, 1e-4f * expected.pdf) << "sample " << i;
        const Vec3 p = got.p / s;
        ASSERT_NEAR(p.x, expected.p.x, 1e-4f) << "sample " << i;
        ASSERT_NEAR(p.y, expected.p.y, 1e-4f) << "sample " << i;
        ASSERT_NEAR(p.z, expected.p.z, 1e-4f) << "sample " << i;
        ASSERT_EQ(got.emitter, expected.emitter) << "sample " << i;
        ASSERT_NEAR(scaled.pdf(got.emitter, ref * s, n, got.p, got.n), got.pdf, 1e-4f * got.pdf) << "sample " << i;
      }
    }
  }
}

}  // namespace
}  // namespace prism
