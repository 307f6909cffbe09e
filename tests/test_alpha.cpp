// glTF alpha modes: MASK cuts holes below the cutoff (for camera and shadow rays alike), BLEND
// lets light through with probability 1 - alpha, the same way on every run.
#include <gtest/gtest.h>

#include "core/pcg32.h"
#include "core/sampler.h"
#include "core/scene.h"
#include "integrators/path_integrator.h"
#include "materials/material_eval.h"
#include "radiance_stats.h"
#include "scene_builders.h"
#include "statistics.h"

namespace prism {
namespace {

// A quad at z = 1 whose left half (u < 0.5) has alpha 0 and right half alpha 1, over a floor.
SceneDesc masked_quad(MaterialDesc::AlphaMode mode) {
  SceneDesc desc;
  ImageDesc img;
  img.width = 2;
  img.height = 1;
  img.channels = 4;
  img.texels = {1, 1, 1, 0, 1, 1, 1, 1};
  desc.images.push_back(img);
  TextureDesc tex;
  tex.image = 0;
  tex.nearest = true;
  desc.textures.push_back(tex);
  const int m = test::add_material(desc, Rgb(0.5f));
  desc.materials[m].base_color_texture.texture = 0;
  desc.materials[m].alpha_mode = mode;
  test::add_quad(desc, Vec3(-1, -1, 1), Vec3(2, 0, 0), Vec3(0, 2, 0), m);
  test::add_quad(desc, Vec3(-5, -5, 0), Vec3(10, 0, 0), Vec3(0, 10, 0), test::add_material(desc, Rgb(0.5f)));
  return desc;
}

TEST(Alpha, MaskCutsHolesForCameraAndShadowRays) {
  const Scene scene(masked_quad(MaterialDesc::AlphaMode::Mask), &material_alpha);
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect(Ray{Vec3(-0.5f, 0, 3), Vec3(0, 0, -1)}, hit));
  EXPECT_NEAR(hit.p.z, 0.0f, 1e-5f);  // through the hole to the floor
  ASSERT_TRUE(scene.intersect(Ray{Vec3(0.5f, 0, 3), Vec3(0, 0, -1)}, hit));
  EXPECT_NEAR(hit.p.z, 1.0f, 1e-5f);  // the opaque half
  EXPECT_FALSE(scene.occluded(Ray{Vec3(-0.5f, 0, 0.01f), Vec3(0, 0, 1), 0, 3}));
  EXPECT_TRUE(scene.occluded(Ray{Vec3(0.5f, 0, 0.01f), Vec3(0, 0, 1), 0, 3}));
  // Without an alpha function every surface is opaque.
  const Scene opaque(masked_quad(MaterialDesc::AlphaMode::Mask));
  EXPECT_TRUE(opaque.occluded(Ray{Vec3(-0.5f, 0, 0.01f), Vec3(0, 0, 1), 0, 3}));
}

TEST(Alpha, BlendTransmitsOneMinusAlphaDeterministically) {
  // A black, 30%-opaque sheet in front of an emitter: on average 70% of the light passes.
  SceneDesc desc;
  const int sheet = test::add_material(desc, Rgb(0.0f));
  desc.materials[sheet].base_alpha = 0.3f;
  desc.materials[sheet].alpha_mode = MaterialDesc::AlphaMode::Blend;
  test::add_quad(desc, Vec3(-5, -5, 1), Vec3(10, 0, 0), Vec3(0, 10, 0), sheet);
  const int light = test::add_material(desc, Rgb(0.0f), Rgb(2.0f));
  test::add_quad(desc, Vec3(-50, -50, -1), Vec3(100, 0, 0), Vec3(0, 100, 0), light);
  const Scene scene(std::move(desc), &material_alpha);
  const PathIntegrator path(4, 1 << 20);
  IndependentSampler sampler(1);
  RayCounters counters;
  Pcg32 rng(9, 9);
  test::RunningStats stats;
  for (int i = 0; i < 40000; ++i) {
    const Ray ray{Vec3(4 * rng.next_float() - 2, 4 * rng.next_float() - 2, 3), Vec3(0, 0, -1)};
    sampler.start_pixel_sample(0, 0, uint64_t(i));
    const float a = path.li(scene, ray, sampler, counters).radiance.x;
    sampler.start_pixel_sample(0, 0, uint64_t(i));
    ASSERT_EQ(path.li(scene, ray, sampler, counters).radiance.x, a);  // the same ray, the same choice
    stats.add(a);
  }
  EXPECT_NEAR(stats.mean(), 0.7 * 2.0, test::kSigmas * stats.standard_error());
}

TEST(Alpha, SpheresCarryAlphaModesToo) {
  // A sphere in front of an emitter: cut out entirely by MASK (alpha 0.2 < cutoff 0.5), or seen
  // through with BLEND alpha 0.3, where the ray crosses two independent surfaces: 0.7^2 passes.
  for (auto mode : {MaterialDesc::AlphaMode::Mask, MaterialDesc::AlphaMode::Blend}) {
    SceneDesc desc;
    const int shell = test::add_material(desc, Rgb(0.0f));
    desc.materials[shell].base_alpha = mode == MaterialDesc::AlphaMode::Mask ? 0.2f : 0.3f;
    desc.materials[shell].alpha_mode = mode;
    test::add_sphere(desc, Vec3(0, 0, 1), 0.8f, shell);
    test::add_quad(desc, Vec3(-50, -50, -1), Vec3(100, 0, 0), Vec3(0, 100, 0), test::add_material(desc, Rgb(0.0f), Rgb(1.0f)));
    const Scene scene(std::move(desc), &material_alpha);
    Pcg32 rng(4, 5);
    const test::RunningStats stats = test::radiance_stats(scene, PathIntegrator(6, 1 << 20), 40000, {.seed = 1}, [&](int) {
      return Ray{Vec3(0.2f * rng.next_float(), 0.2f * rng.next_float(), 3), Vec3(0, 0, -1)};
    });
    if (mode == MaterialDesc::AlphaMode::Mask) {
      EXPECT_EQ(stats.mean(), 1.0);
    } else {
      EXPECT_NEAR(stats.mean(), 0.49, test::kSigmas * stats.standard_error());
    }
  }
}

}  // namespace
}  // namespace prism
