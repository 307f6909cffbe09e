// KHR_lights_punctual: units (candela and lux against analytic radiance), spot falloff, range
// window, and loading from glTF with node transforms.
#include <gtest/gtest.h>

#include <cmath>

#include "core/constants.h"
#include "core/punctual_light.h"
#include "core/sampler.h"
#include "core/scene.h"
#include "gltf_writer.h"
#include "integrators/path_integrator.h"
#include "io/errors.h"
#include "io/gltf_loader.h"
#include "radiance_stats.h"
#include "scene_builders.h"
#include "statistics.h"

namespace prism {
namespace {

constexpr double kAlbedo = 0.5;

// Radiance leaving the Lambertian plane z = 0 at (x, y) toward +z (direct light only).
double plane_radiance(const Scene& scene, float x, float y) {
  const test::RunningStats stats = test::radiance_stats(scene, PathIntegrator(1, 1 << 20), 64, {.seed = 3},
                                                        [&](int) { return Ray{Vec3(x, y, 0.01f), Vec3(0, 0, -1)}; });
  EXPECT_LT(stats.standard_error(), 1e-6 * std::max(1e-3, stats.mean()));  // one light, no choice: exact
  return stats.mean();
}

SceneDesc plane_with(const PunctualLightDesc& light) {
  SceneDesc desc;
  test::add_quad(desc, Vec3(-50, -50, 0), Vec3(100, 0, 0), Vec3(0, 100, 0), test::add_material(desc, Rgb(float(kAlbedo))));
  desc.lights.push_back(light);
  return desc;
}

TEST(PunctualLights, PointLightInCandelaGivesAnalyticRadiance) {
  // E = I cos(theta) / d^2 lux; a Lambertian surface reflects L = albedo E / pi nits.
  PunctualLightDesc l;
  l.position = Vec3(0, 0, 2);
  l.intensity = Rgb(100.0f);
  const Scene scene(plane_with(l));
  for (float x : {0.0f, 1.0f, 3.0f}) {
    const double d2 = double(x) * x + 4.0, cos_t = 2.0 / std::sqrt(d2);
    EXPECT_NEAR(plane_radiance(scene, x, 0), kAlbedo / kPi * 100.0 * cos_t / d2, 1e-5) << x;
  }
}

TEST(PunctualLights, DirectionalLightInLux) {
  PunctualLightDesc l;
  l.type = LightType::Directional;
  l.direction = normalize(Vec3(1, 0, -1));  // 45 degrees
  l.intensity = Rgb(1000.0f);
  const Scene scene(plane_with(l));
  EXPECT_NEAR(plane_radiance(scene, 0.3f, -2.0f), kAlbedo / kPi * 1000.0 * std::sqrt(0.5), 1e-3);
}

TEST(PunctualLights, SpotConeFalloff) {
  PunctualLightDesc l;
  l.type = LightType::Spot;
  l.position = Vec3(0, 0, 1);
  l.direction = Vec3(0, 0, -1);
  l.intensity = Rgb(10.0f);
  l.cos_inner = std::cos(0.2f);
  l.cos_outer = std::cos(0.5f);
  const Scene scene(plane_with(l));
  auto expected = [&](float angle, float falloff) {
    const double d = 1.0 / std::cos(angle);
    return kAlbedo / kPi * 10.0 * falloff * std::cos(angle) / (d * d);
  };
  // Inside the inner cone: full intensity; outside the outer cone: nothing.
  EXPECT_NEAR(plane_radiance(scene, std::tan(0.1f), 0), expected(0.1f, 1.0f), 1e-5);
  EXPECT_EQ(plane_radiance(scene, std::tan(0.6f), 0), 0.0);
  // Between: the square of the linear ramp in cos(angle).
  const float a = 0.35f;
  const float t = (std::cos(a) - l.cos_outer) / (l.cos_inner - l.cos_outer);
  // The ramp differences cosines of nearby angles: float loses ~1e-5 relative there.
  EXPECT_NEAR(plane_radiance(scene, std::tan(a), 0), expected(a, t * t), 1e-4 * expected(a, t * t));
}

TEST(PunctualLights, RangeWindow) {
  EXPECT_EQ(range_window(5.0f, 0.0f), 1.0f);  // no range: inverse square only
  EXPECT_FLOAT_EQ(range_window(1.0f, 2.0f), 1.0f - 1.0f / 16.0f);
  EXPECT_EQ(range_window(2.0f, 2.0f), 0.0f);
  EXPECT_EQ(range_window(3.0f, 2.0f), 0.0f);
  PunctualLightDesc l;
  l.position = Vec3(0, 0, 1);
  l.intensity = Rgb(10.0f);
  l.range = 1.5f;
  const Scene scene(plane_with(l));
  EXPECT_EQ(plane_radiance(scene, 2.0f, 0), 0.0);  // 2.24 away: beyond the range
  EXPECT_NEAR(plane_radiance(scene, 0, 0), kAlbedo / kPi * 10.0 * (1.0 - std::pow(1.0 / 1.5, 4)), 1e-5);
}

TEST(PunctualLights, ShadowedByGeometry) {
  PunctualLightDesc l;
  l.position = Vec3(0, 0, 2);
  l.intensity = Rgb(100.0f);
  SceneDesc desc = plane_with(l);
  test::add_quad(desc, Vec3(-0.5f, -0.5f, 1), Vec3(1, 0, 0), Vec3(0, 1, 0), test::add_material(desc, Rgb(0.5f)));
  const Scene scene(std::move(desc));
  EXPECT_EQ(plane_radiance(scene, 0.1f, 0.1f), 0.0);
  EXPECT_GT(plane_radiance(scene, 3.0f, 0.0f), 0.0);
}

TEST(PunctualLights, LoadedFromGltfWithNodeTransforms) {
  const std::string dir = test::make_temp_dir("lights");
  test::GltfWriter w;
  w.doc()["extensionsUsed"] = {"KHR_lights_punctual"};
  w.doc()["extensionsRequired"] = {"KHR_lights_punctual"};
  w.doc()["extensions"]["KHR_lights_punctual"]["lights"] = nlohmann::json::array(
      {{{"type", "spot"}, {"color", {1, 0.5, 0.25}}, {"intensity", 40}, {"range", 12},
        {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.4}}}},
       {{"type", "directional"}}});
  const double h = std::sqrt(0.5);
  const int spot = w.add_node({{"translation", {1, 2, 3}}, {"rotation", {-h, 0, 0, h}},  // -Z turned to -Y
                               {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  const int sun = w.add_node({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  w.set_scene_nodes({spot, sun, w.add_node({{"mesh", w.add_mesh(w.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0}))}})});
  Diagnostics diag;
  const SceneDesc s = load_gltf(w.write(dir, "scene"), diag);
  ASSERT_EQ(s.lights.size(), 2u);
  const PunctualLightDesc& l = s.lights[0];
  EXPECT_EQ(l.type, LightType::Spot);
  EXPECT_NEAR(l.position.y, 2.0f, 1e-6f);
  EXPECT_NEAR(l.direction.y, -1.0f, 1e-6f);
  EXPECT_NEAR(l.intensity.y, 20.0f, 1e-5f);
  EXPECT_FLOAT_EQ(l.range, 12.0f);
  EXPECT_NEAR(l.cos_outer, std::cos(0.4f), 1e-6f);
  EXPECT_EQ(s.lights[1].type, LightType::Directional);
  EXPECT_EQ(s.lights[1].intensity, Rgb(1.0f));  // colour and intensity default to 1
  EXPECT_NEAR(s.lights[1].direction.z, -1.0f, 1e-6f);
  EXPECT_TRUE(s.features().punctual_lights);

  w.doc()["extensions"]["KHR_lights_punctual"]["lights"][0]["spot"]["innerConeAngle"] = 0.5;  // inner > outer
  EXPECT_THROW(load_gltf(w.write(dir, "bad"), diag), InputError);
}

}  // namespace
}  // namespace prism
