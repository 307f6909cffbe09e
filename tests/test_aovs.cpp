// AOVs: each layer means what its name says on a scene whose answers are known, the light layers
// add up to the beauty, and crops and sample slices reproduce a whole render.
#include <gtest/gtest.h>

#include <cmath>

#include "core/camera.h"
#include "core/mip_levels.h"
#include "core/renderer.h"
#include "core/scene.h"
#include "integrators/path_integrator.h"
#include "integrators/whitted_integrator.h"
#include "gltf_writer.h"
#include "io/exr_reader.h"
#include "io/exr_writer.h"
#include "io/film_state.h"
#include "io/render_layers.h"
#include "aov_scene.h"
#include "scene_builders.h"

namespace prism {
namespace {

constexpr int kSize = 32;
using test::aov_scene;
using test::kAlbedo;
using test::kLight;
using test::top_camera;

Film render_aovs(const Scene& scene, RenderSettings s, const Integrator& integrator) {
  const PixelWindow window = s.crop.empty() ? PixelWindow{0, 0, s.width, s.height} : s.crop;
  Film film(window.width(), window.height(), s.aovs);
  film.set_cryptomatte_ids(object_cryptomatte_ids(scene.desc()), material_cryptomatte_ids(scene.desc()));
  render(scene, Camera(top_camera(), s.width, s.height), integrator, s, film);
  return film;
}

RenderSettings aov_settings() {
  RenderSettings s;
  s.width = s.height = kSize;
  s.spp = 16;
  s.seed = 5;
  s.aovs = parse_aovs("all");
  return s;
}

// Whether the test scene's ball stands between floor point p and a corner or the centre of the light.
bool ball_shades(const Vec3& p) {
  const Vec3 c = test::kLightCorner, u = test::kLightEdgeU, v = test::kLightEdgeV;
  for (const Vec3 q : {c, c + u, c + v, c + u + v, c + (u + v) * 0.5f}) {
    const Vec3 d = normalize(q - p);
    const Vec3 to_ball = test::kBallCenter - p;
    const Vec3 off_axis = to_ball - d * dot(to_ball, d);
    if (dot(to_ball, d) > 0 && length(off_axis) < test::kBallRadius) return true;
  }
  return false;
}

// split: the path tracer's continuations per camera sample, whose light layers are their means.
void expect_every_layer_means_what_it_says(int split) {
  SCOPED_TRACE("split " + std::to_string(split));
  const Scene scene(aov_scene());
  PathIntegrator path(8, 3);
  path.set_split(split);
  const Film film = render_aovs(scene, aov_settings(), path);
  ExrImage image;
  add_render_layers(film, &scene.desc(), LayerOptions{ExrPixelType::Float, 6}, image);
  auto channel = [&](const char* name) {
    const ExrChannel* c = image.find(name);
    EXPECT_NE(c, nullptr) << name;
    return c ? c->values : std::vector<float>(size_t(kSize) * kSize);
  };
  const auto R = channel("R"), G = channel("G"), A = channel("A"), Z = channel("Z");
  const auto Nz = channel("N.Z"), Px = channel("P.X"), Py = channel("P.Y"), Pz = channel("P.Z"), albedo_r = channel("albedo.R"), albedo_b = channel("albedo.B");
  const auto emission_r = channel("emission.R"), direct_r = channel("direct.R"), indirect_r = channel("indirect.R");
  const auto emission_g = channel("emission.G"), direct_g = channel("direct.G"), indirect_g = channel("indirect.G");
  const auto object = channel("object_id.V"), material = channel("material_id.V"), spp = channel("spp.V");
  const auto variance_r = channel("variance.R"), crypto_cov0 = channel("CryptoObject00.G"),
             crypto_cov1 = channel("CryptoObject00.A");
  int floor_pixels = 0, light_pixels = 0, ball_pixels = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const size_t i = size_t(y) * kSize + x;
      // The light layers add up to the beauty.
      EXPECT_NEAR(emission_r[i] + direct_r[i] + indirect_r[i], R[i], 1e-5f * (1 + R[i])) << x << "," << y;
      EXPECT_NEAR(emission_g[i] + direct_g[i] + indirect_g[i], G[i], 1e-5f * (1 + G[i]));
      EXPECT_EQ(spp[i], 16.0f);
      EXPECT_FLOAT_EQ(variance_r[i], film.variance_of_mean(x, y).x);
      EXPECT_NEAR(crypto_cov0[i] + crypto_cov1[i], A[i], 1e-6f) << "at most two objects per pixel here";
      // The nearest hit's ids, and its planar depth.
      if (A[i] == 0) {
        EXPECT_EQ(Z[i], kBackgroundDepth);
        EXPECT_EQ(object[i], -1.0f);
        continue;
      }
      if (A[i] < 1) continue;  // an edge: averaged layers mix what the samples saw
      if (object[i] == 0 && crypto_cov0[i] == 1) {  // all floor
        ++floor_pixels;
        EXPECT_NEAR(Z[i], 5.0f, 1e-5f);
        EXPECT_NEAR(Nz[i], 1.0f, 1e-6f);
        EXPECT_NEAR(Pz[i], 0.0f, 1e-6f);
        EXPECT_NEAR(albedo_r[i], kAlbedo.x, 1e-6f);
        EXPECT_NEAR(albedo_b[i], kAlbedo.z, 1e-6f);
        EXPECT_EQ(material[i], 0.0f);
        EXPECT_EQ(emission_r[i], 0.0f);
        // Lit directly, unless the ball hides much of the light: in its penumbra 16 light samples
        // can all land behind it (at pixel 9,26 95% of the light is hidden).
        if (!ball_shades(Vec3(Px[i], Py[i], Pz[i]))) EXPECT_GT(direct_r[i], 0.0f) << x << "," << y;
      } else if (object[i] == 1 && crypto_cov0[i] == 1) {  // the light, seen from behind: it faces the floor
        ++light_pixels;
        EXPECT_NEAR(Z[i], 3.0f, 1e-5f);
        EXPECT_EQ(material[i], 1.0f);
        EXPECT_NEAR(Nz[i], -1.0f, 1e-6f);
        EXPECT_EQ(emission_r[i], 0.0f) << "one-sided emitters shine from their front only";
      } else if (object[i] == 2 && crypto_cov0[i] == 1) {
        ++ball_pixels;
        EXPECT_EQ(material[i], 2.0f) << "the default material is numbered after the scene's";
        EXPECT_GT(Z[i], 4.0f - 1e-5f);
        EXPECT_LT(Z[i], 5.0f);
      }
    }
  EXPECT_GT(floor_pixels, 100);
  EXPECT_GT(ball_pixels, 5);
  EXPECT_GT(light_pixels, 10);
}

TEST(Aovs, EveryLayerMeansWhatItSays) {
  expect_every_layer_means_what_it_says(1);
  expect_every_layer_means_what_it_says(3);
}

TEST(Aovs, EmissionSeenDirectlyIsItsOwnLayer) {
  SceneDesc desc = aov_scene();
  desc.materials[1].double_sided = true;  // now the camera sees the light's emission too
  const Scene scene(std::move(desc));
  for (const std::string integrator : {"path", "whitted"}) {
    const PathIntegrator path(8, 3);
    const WhittedIntegrator whitted(8);
    const Film film = render_aovs(scene, aov_settings(), integrator == "path" ? static_cast<const Integrator&>(path) : whitted);
    const std::vector<float> emission = film.resolve_average(Aov::Emission, 0);
    int light_pixels = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        if (film.nearest_object(x, y) != 1 || film.crypto_objects()[size_t(y) * kSize + x].size() != 1) continue;
        ++light_pixels;
        EXPECT_FLOAT_EQ(emission[size_t(y) * kSize + x], kLight.x) << integrator;
      }
    EXPECT_GT(light_pixels, 10) << integrator;
  }
}

// With MIP levels, the camera's ray cones reach the texture lookups: a floor textured with a
// checker of single texels, each pixel spanning about 13 of them, reads levels of exact grey
// (every level from the first is 0.5 in every texel), so every floor pixel's albedo is exactly half
// the factor, where the full-size checker leaves the pixels' means scattered around it.
TEST(Aovs, TrilinearFilteringReadsTheLevelsAPixelSpans) {
  SceneDesc desc = aov_scene();
  ImageDesc& checker = desc.images.emplace_back();
  checker.width = checker.height = 512;  // over the floor's 6 m: 13 texels per pixel at 5 m
  checker.channels = 1;
  for (int y = 0; y < 512; ++y)
    for (int x = 0; x < 512; ++x) checker.texels.push_back(float((x + y) % 2));
  desc.textures.push_back(TextureDesc{});
  desc.textures[0].image = 0;
  desc.materials[0].base_color_texture.texture = 0;
  const auto floor_albedo_spread = [&](bool mipped, const std::string& integrator) {
    SceneDesc d = desc;
    if (mipped) build_mip_levels(d.images[0]);
    const Scene scene(std::move(d));
    const PathIntegrator path(8, 3);
    const WhittedIntegrator whitted(8);
    const Film film =
        render_aovs(scene, aov_settings(), integrator == "path" ? static_cast<const Integrator&>(path) : whitted);
    const std::vector<float> albedo = film.resolve_average(Aov::Albedo, 0);
    float spread = 0;
    int floor_pixels = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        if (film.nearest_object(x, y) != 0 || film.crypto_objects()[size_t(y) * kSize + x].size() != 1) continue;
        ++floor_pixels;
        spread = std::max(spread, std::abs(albedo[size_t(y) * kSize + x] - 0.5f * kAlbedo.x));
      }
    EXPECT_GT(floor_pixels, 100);
    return spread;
  };
  for (const std::string integrator : {"path", "whitted"}) {
    EXPECT_LT(floor_albedo_spread(true, integrator), 1e-6f) << integrator;
    EXPECT_GT(floor_albedo_spread(false, integrator), 0.01f) << integrator << ": the checker is not resolved at 16 spp";
  }
}

TEST(Aovs, ACropRendersThePixelsOfTheWholeImage) {
  const Scene scene(aov_scene());
  const PathIntegrator path(8, 3);
  const Film whole = render_aovs(scene, aov_settings(), path);
  RenderSettings s = aov_settings();
  s.crop = {5, 7, 21, 30};
  const Film crop = render_aovs(scene, s, path);
  ASSERT_EQ(crop.width(), 16);
  ASSERT_EQ(crop.height(), 23);
  for (int y = 0; y < crop.height(); ++y)
    for (int x = 0; x < crop.width(); ++x) {
      float a[4], b[4];
      crop.mean(x, y, a);
      whole.mean(x + 5, y + 7, b);
      for (int c = 0; c < 4; ++c) ASSERT_EQ(a[c], b[c]) << x << "," << y;
      ASSERT_EQ(crop.nearest_depth(x, y), whole.nearest_depth(x + 5, y + 7));
      for (int k = 0; k < crop.average_slots(); ++k)
        ASSERT_EQ(crop.average_sums(x, y)[k], whole.average_sums(x + 5, y + 7)[k]);
    }
}

TEST(Aovs, SampleSlicesMergeIntoTheWholeRender) {
  const Scene scene(aov_scene());
  PathIntegrator path(8, 3);
  path.set_split(2);  // the slices' continuations are the whole render's too
  const Film whole = render_aovs(scene, aov_settings(), path);
  RenderSettings s = aov_settings();
  s.spp = 4;
  Film merged = render_aovs(scene, s, path);
  for (int slice = 1; slice < 4; ++slice) {
    s.first_sample = uint64_t(4 * slice);
    merged.merge(render_aovs(scene, s, path));
  }
  const std::vector<float> a = merged.resolve_rgba(), b = whole.resolve_rgba();
  for (size_t i = 0; i < a.size(); ++i) ASSERT_NEAR(a[i], b[i], 1e-6f * (1 + std::abs(b[i]))) << i;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      ASSERT_EQ(merged.sample_count(x, y), 16u);
      ASSERT_EQ(merged.nearest_depth(x, y), whole.nearest_depth(x, y));
      ASSERT_EQ(merged.nearest_object(x, y), whole.nearest_object(x, y));
      const Rgb va = merged.variance_of_mean(x, y), vb = whole.variance_of_mean(x, y);
      ASSERT_NEAR(va.x, vb.x, 1e-5f * (vb.x + 1e-6f));
    }
  ExrImage ia, ib;
  add_render_layers(merged, &scene.desc(), {}, ia);
  add_render_layers(whole, &scene.desc(), {}, ib);
  for (const char* name : {"CryptoObject00.R", "CryptoObject00.G", "CryptoObject01.R", "CryptoMaterial00.G"})
    EXPECT_EQ(ia.find(name)->values, ib.find(name)->values) << name;
}

// A film written with its state and read back is the same film, accumulator for accumulator; one
// written without rebuilds from its layers to float rounding.
TEST(Aovs, FilmsRoundTripThroughExrFiles) {
  const Scene scene(aov_scene());
  const PathIntegrator path(8, 3);
  RenderSettings s = aov_settings();
  s.crop = {3, 4, 29, 20};
  const Film film = render_aovs(scene, s, path);
  const std::string dir = test::make_temp_dir("film_state");
  for (bool with_state : {true, false}) {
    ExrImage image;
    image.display = {0, 0, kSize, kSize};
    image.data = s.crop;
    image.attributes.push_back({"prism/aovs", std::string("all")});
    add_render_layers(film, &scene.desc(), LayerOptions{ExrPixelType::Float, 6}, image);
    if (with_state) add_film_state(film, image);
    write_exr(dir + "/film.exr", image);
    const Film back = film_from_image(read_exr(dir + "/film.exr"), dir + "/film.exr");
    ASSERT_EQ(back.width(), film.width());
    ASSERT_EQ(back.height(), film.height());
    for (int y = 0; y < film.height(); ++y)
      for (int x = 0; x < film.width(); ++x) {
        const Film::Pixel &a = back.pixel(x, y), &b = film.pixel(x, y);
        ASSERT_EQ(a.count, b.count);
        ASSERT_EQ(back.nearest_depth(x, y), film.nearest_depth(x, y));
        ASSERT_EQ(back.nearest_object(x, y), film.nearest_object(x, y));
        for (int c = 0; c < 4; ++c) {
          if (with_state) ASSERT_EQ(a.sum[c], b.sum[c]);
          else ASSERT_NEAR(a.sum[c], b.sum[c], 1e-6 * (1 + b.sum[c]));
        }
        for (int k = 0; k < film.average_slots(); ++k) {
          if (with_state) ASSERT_EQ(back.average_sums(x, y)[k], film.average_sums(x, y)[k]);
          else ASSERT_NEAR(back.average_sums(x, y)[k], film.average_sums(x, y)[k], 1e-5 * (1 + std::abs(film.average_sums(x, y)[k])));
        }
        const Rgb va = back.variance_of_mean(x, y), vb = film.variance_of_mean(x, y);
        if (with_state) ASSERT_EQ(va.x, vb.x);
        else ASSERT_NEAR(va.x, vb.x, 1e-4 * (vb.x + 1e-6));
      }
  }
}

}  // namespace
}  // namespace prism
