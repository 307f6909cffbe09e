// Environment light: the white furnace, orientation of equirectangular maps, importance sampling
// against its pdf, and unbiased lighting of a plane under a map with a hot spot.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>

#include "chi_square.h"
#include "core/constants.h"
#include "core/emitters.h"
#include "core/environment_light.h"
#include "core/pcg32.h"
#include "core/sampler.h"
#include "core/sampling.h"
#include "core/scene.h"
#include "integrators/path_integrator.h"
#include "integrators/whitted_integrator.h"
#include "io/errors.h"
#include "io/exr_writer.h"
#include "io/job_file.h"
#include "radiance_stats.h"
#include "gltf_writer.h"
#include "scene_builders.h"
#include "statistics.h"

namespace prism {
namespace {

// A 64 x 32 map: dim blue sky, a small bright warm spot at u = 0.7, v = 0.3.
ImageDesc hot_spot_map() {
  ImageDesc img;
  img.width = 64;
  img.height = 32;
  img.channels = 3;
  img.texels.resize(64 * 32 * 3);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool spot = std::abs(x - 45) <= 1 && std::abs(y - 9) <= 1;
      const Rgb c = spot ? Rgb(400, 300, 200) : Rgb(0.2f, 0.3f, 0.6f) * (1.0f + 0.02f * float(y));
      for (int k = 0; k < 3; ++k) img.texels[(y * 64 + x) * 3 + k] = c[k];
    }
  return img;
}

SceneDesc with_environment(SceneDesc desc, const Rgb& color, bool map, float rotation = 0) {
  desc.environment.present = true;
  desc.environment.color = color;
  desc.environment.rotation = rotation;
  if (map) {
    desc.environment.image = static_cast<int>(desc.images.size());
    desc.images.push_back(hot_spot_map());
  }
  return desc;
}

test::RunningStats estimate(const Scene& scene, const Integrator& integrator, const Ray& ray, int samples) {
  return test::radiance_stats(scene, integrator, samples, {.seed = 11, .x = 1, .y = 2, .channel = 1},
                              [&](int) { return ray; });
}

TEST(Environment, WhiteFurnaceHidesAWhiteSphere) {
  // Under a uniform sky of radiance 1, a convex Lambertian sphere of albedo a reflects exactly a
  // (it sees only sky): with a = 1 it vanishes against the background.
  for (float albedo : {1.0f, 0.5f}) {
    SceneDesc desc;
    test::add_sphere(desc, Vec3(0, 0, 0), 1.0f, test::add_material(desc, Rgb(albedo)));
    const Scene scene(with_environment(std::move(desc), Rgb(1.0f), false));
    const PathIntegrator path(50, 3);
    const test::RunningStats s = estimate(scene, path, Ray{Vec3(0.3f, 0.2f, 5), Vec3(0, 0, -1)}, 20000);
    EXPECT_NEAR(s.mean(), albedo, test::kSigmas * s.standard_error() + 1e-6) << albedo;
    const test::RunningStats sky = estimate(scene, path, Ray{Vec3(3, 0, 5), Vec3(0, 0, -1)}, 10);
    EXPECT_EQ(sky.mean(), 1.0);
    const WhittedIntegrator whitted(8);
    EXPECT_EQ(estimate(scene, whitted, Ray{Vec3(3, 0, 5), Vec3(0, 0, -1)}, 1).mean(), 1.0);
  }
}

TEST(Environment, EquirectangularOrientation) {
  SceneDesc desc = with_environment(SceneDesc{}, Rgb(1.0f), true);
  const EnvironmentLight env(desc);
  // The centre of the map looks down -Z, the top row is +Y, u grows toward +X.
  EXPECT_NEAR(env.direction_to_uv(Vec3(0, 0, -1)).x, 0.5f, 1e-6f);
  EXPECT_NEAR(env.direction_to_uv(Vec3(1, 0, 0)).x, 0.75f, 1e-6f);
  EXPECT_NEAR(env.direction_to_uv(Vec3(0, 1, 0)).y, 0.0f, 1e-6f);
  EXPECT_NEAR(env.direction_to_uv(Vec3(0, -1, 0)).y, 1.0f, 1e-6f);
  // Round trip under a rotation of the sky by +90 degrees about +Y.
  SceneDesc rotated = with_environment(SceneDesc{}, Rgb(1.0f), true, kPiOver2);
  const EnvironmentLight r(rotated);
  for (Vec3 w : {Vec3(0.3f, 0.5f, -0.8f), Vec3(-0.9f, 0.1f, 0.2f)}) {
    w = normalize(w);
    const Vec3 back = r.uv_to_direction(r.direction_to_uv(w));
    EXPECT_NEAR(back.x, w.x, 1e-5f);
    EXPECT_NEAR(back.z, w.z, 1e-5f);
  }
  // Counter-clockwise seen from above: the map's centre, toward -Z before, now faces -X.
  EXPECT_NEAR(r.direction_to_uv(Vec3(-1, 0, 0)).x, 0.5f, 1e-5f);
  // The map coordinates of any direction (poles and seams included) are its angles in double to
  // within a few float ulps of 1, and the map's direction at uv is the point on the sphere.
  Pcg32 rng(5, 6);
  for (int i = 0; i < 20000; ++i) {
    Vec3 w = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    if (i % 4 == 1) w = normalize(Vec3(w.x * 1e-4f, w.y, w.z * 1e-4f));  // near a pole
    if (i % 4 == 2) w = normalize(Vec3(w.x * 1e-4f, w.y, -std::abs(w.z)));  // near the seam
    const Vec2 uv = env.direction_to_uv(w);
    const double u = 0.5 + std::atan2(double(w.x), -double(w.z)) / (2 * M_PI);
    // (acos of w.y would be the polar angle of a unit w, but w.y in float is 1 - 6e-8 k near +Y.)
    const double v = std::atan2(std::hypot(double(w.x), double(w.z)), double(w.y)) / M_PI;
    ASSERT_NEAR(uv.x, u, 4e-7) << w.x << " " << w.y << " " << w.z;
    ASSERT_NEAR(uv.y, v, 4e-7) << w.x << " " << w.y << " " << w.z;
    const Vec3 back = env.uv_to_direction(uv);
    ASSERT_NEAR(length(back), 1.0f, 1e-6f);
    ASSERT_LT(length(back - w), 2e-6f) << w.x << " " << w.y << " " << w.z;
  }
}

TEST(Environment, MapSamplingMatchesItsPdf) {
  for (float rotation : {0.0f, 0.7f}) {
    SceneDesc desc = with_environment(SceneDesc{}, Rgb(1.0f, 0.5f, 2.0f), true, rotation);
    const EnvironmentLight env(desc);
    const std::string why = test::chi_square_sphere(
        [&](float, Vec2 u) -> std::optional<test::DirectionSample> {
          const auto [w, seen] = env.sample(u);
          // One mapping of w serves both: they agree with the separate lookups.
          EXPECT_EQ(seen.pdf, env.pdf(w));
          EXPECT_EQ(seen.radiance, env.radiance(w));
          if (!(seen.pdf > 0)) return std::nullopt;
          return test::DirectionSample{w, seen.pdf};
        },
        [&](const Vec3& w) { return env.pdf(w); });
    EXPECT_EQ(why, "") << rotation;
  }
}

// A batch of draws (staged, several draws' lookups at a time) gives each draw exactly what it
// gives alone, for batches longer than one stage and not a multiple of it.
TEST(Environment, BatchedDrawsMatchSingleDraws) {
  SceneDesc desc = with_environment(SceneDesc{}, Rgb(1.0f, 0.5f, 2.0f), true, 0.3f);
  const EnvironmentLight env(desc);
  Pcg32 rng(11, 12);
  std::vector<Vec2> u(21);
  for (Vec2& d : u) d = {rng.next_float(), rng.next_float()};
  u[0] = {0.0f, 0.0f};
  u[1] = {0x1.fffffep-1f, 0x1.fffffep-1f};
  std::vector<EnvironmentLight::Sample> batch(u.size());
  env.sample(u.data(), int(u.size()), batch.data());
  for (size_t i = 0; i < u.size(); ++i) {
    const EnvironmentLight::Sample one = env.sample(u[i]);
    EXPECT_EQ(batch[i].wi, one.wi) << i;
    EXPECT_EQ(batch[i].seen.radiance, one.seen.radiance) << i;
    EXPECT_EQ(batch[i].seen.pdf, one.seen.pdf) << i;
  }
}

// Light samples of a map's sky can be drawn ahead of the vertex (PathIntegrator::li_packet draws a
// packet's together): environment_map_draw says so for exactly the draws that choose the sky, and
// the sample drawn from what it hands the map is the one Emitters::sample draws itself. Under both
// light samplers, with area and punctual lights beside the sky.
TEST(Environment, LightSamplesDrawnAheadAreTheVertexsOwn) {
  SceneDesc desc = with_environment(SceneDesc{}, Rgb(1.0f, 0.5f, 2.0f), true, 0.3f);
  const int lamp = test::add_material(desc, Rgb(0.0f), Rgb(3.0f));
  for (int q = 0; q < 6; ++q)
    test::add_quad(desc, Vec3(float(q) - 3, 2, 0), Vec3(0.3f, 0, 0), Vec3(0, 0, 0.3f), lamp);
  PunctualLightDesc point;
  point.type = LightType::Point;
  point.position = Vec3(0, 3, 1);
  point.intensity = Rgb(20.0f);
  desc.lights.push_back(point);
  for (LightSampling how : {LightSampling::Tree, LightSampling::Power}) {
    const Emitters emitters(desc, how);
    Pcg32 rng(13, 14);
    int sky = 0, other = 0;
    for (int i = 0; i < 4000; ++i) {
      const Vec3 ref(4 * rng.next_float() - 2, 0, 4 * rng.next_float() - 2);
      const float u_spare = rng.next_float();
      const Vec2 u{rng.next_float(), rng.next_float()};
      const EmitterSample at_vertex = emitters.sample(ref, Vec3(0, 1, 0), u_spare, u);
      const std::optional<Vec2> ahead = emitters.environment_map_draw(u_spare, u);
      ASSERT_EQ(ahead.has_value(), at_vertex.infinite) << i;
      if (!ahead) {
        ++other;
        continue;
      }
      ++sky;
      const EnvironmentLight::Sample drawn = emitters.environment().sample(*ahead);
      const EmitterSample given = emitters.sample(ref, Vec3(0, 1, 0), u_spare, u, &drawn);
      EXPECT_EQ(given.wi, at_vertex.wi) << i;
      EXPECT_EQ(given.pdf, at_vertex.pdf) << i;
      EXPECT_EQ(given.incident, at_vertex.incident) << i;
    }
    // Both kinds of light are drawn often enough for the check to mean something.
    EXPECT_GT(sky, 400);
    EXPECT_GT(other, 400);
  }
}

TEST(Environment, PlaneUnderAMapIsLitWithoutBias) {
  // Irradiance of an upward-facing plane: E = integral of L cos over the upper hemisphere,
  // integrated finely here; a Lambertian plane then reflects albedo E / pi.
  SceneDesc desc;
  test::add_quad(desc, Vec3(-50, 0, 50), Vec3(100, 0, 0), Vec3(0, 0, -100), test::add_material(desc, Rgb(0.5f)));
  desc = with_environment(std::move(desc), Rgb(1.0f), true, 0.3f);
  const Scene scene(std::move(desc));
  const EnvironmentLight& env = scene.emitters().environment();
  double E = 0;
  const int n = 1500;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double theta = (i + 0.5) / n * kPiOver2, phi = (j + 0.5) / (2 * n) * kTwoPi;
      const Vec3 w(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)), float(std::sin(theta) * std::sin(phi)));
      E += env.radiance(w).y * std::cos(theta) * std::sin(theta) * (kPiOver2 / n) * (kTwoPi / (2 * n));
    }
  const PathIntegrator path(1, 1 << 20);
  const test::RunningStats s = estimate(scene, path, Ray{Vec3(0.2f, 1, 0.1f), Vec3(0, -1, 0)}, 100000);
  EXPECT_NEAR(s.mean(), 0.5 * E / kPi, test::kSigmas * s.standard_error() + 2e-3 * E);
}

TEST(Environment, FromJobFileAndErrors) {
  const std::string dir = test::make_temp_dir("env");
  write_exr(dir + "/sky.exr", 4, 2, std::vector<float>(4 * 2 * 4, 0.5f), {});
  Diagnostics diag;
  const JobFile job = parse_job_json(R"({"environment": {"map": "sky.exr", "intensity": 2, "rotation": 90}})",
                                     dir + "/job.json", diag);
  SceneDesc scene;
  apply_environment(job.environment, scene);
  ASSERT_TRUE(scene.environment.present);
  EXPECT_FLOAT_EQ(scene.environment.color.x, 2.0f);
  EXPECT_NEAR(scene.environment.rotation, kPiOver2, 1e-6f);
  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_FLOAT_EQ(scene.images[0].texels[0], 0.5f);  // float EXR stays linear
  EnvironmentSpec missing;
  missing.map = dir + "/nope.exr";
  EXPECT_THROW(apply_environment(missing, scene), InputError);
  EXPECT_THROW(parse_job_json(R"({"environment": {}})", dir + "/job.json", diag), InputError);
}

// A half-float EXR map keeps its halves (half the memory of floats), and is checked for negative
// and non-finite pixels like any other map.
TEST(Environment, HalfMapKeepsItsHalvesAndIsChecked) {
  const std::string dir = test::make_temp_dir("envhalf");
  const auto write_half_exr = [&](const std::string& name, float last) {
    std::vector<float> pixels(8 * 4 * 3, 0.75f);
    pixels.back() = last;
    auto out = OIIO::ImageOutput::create(dir + "/" + name);
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(dir + "/" + name, OIIO::ImageSpec(8, 4, 3, OIIO::TypeDesc::HALF)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
  };
  write_half_exr("good.exr", 2.5f);
  write_half_exr("negative.exr", -1.0f);
  write_half_exr("infinite.exr", INFINITY);
  EnvironmentSpec spec;
  spec.map = dir + "/good.exr";
  SceneDesc scene;
  apply_environment(spec, scene);
  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_TRUE(scene.images[0].holds_halves());
  EXPECT_EQ(scene.images[0].texel(7, 3).rgb.z, 2.5f);
  for (const char* bad : {"negative.exr", "infinite.exr"}) {
    spec.map = dir + "/" + bad;
    SceneDesc other;
    try {
      apply_environment(spec, other);
      ADD_FAILURE() << bad << ": expected an InputError";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("negative or non-finite pixels"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace prism
