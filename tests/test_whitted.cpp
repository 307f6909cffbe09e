// The Whitted integrator: exact where its splitting is exact, and in agreement with the path
// tracer on point lights, mirrors, glass and plastic with diffuse surfaces lit only directly.
#include <gtest/gtest.h>

#include <cmath>

#include "core/camera.h"
#include "core/renderer.h"
#include "core/sampler.h"
#include "core/scene.h"
#include "integrators/path_integrator.h"
#include "integrators/whitted_integrator.h"
#include "scene_builders.h"
#include "statistics.h"

namespace prism {
namespace {

TEST(Whitted, SplitsAtGlassExactlyAsTheClosedForm) {
  // The glass cube of BeerLambert.ColouredGlassCubeMatchesClosedFormAlongItsAxis, traced once:
  // Whitted sums every internal reflection deterministically.
  const double n = 1.5, d = 0.8, le = 3.0, colour = 0.7;
  SceneDesc desc;
  const int light = test::add_material(desc, Rgb(0.0f), Rgb(float(le)));
  test::add_quad(desc, Vec3(-50, -50, -3), Vec3(100, 0, 0), Vec3(0, 100, 0), light);
  test::add_box(desc, Vec3(-1, -1, float(-d)), Vec3(1, 1, 0), test::add_glass(desc, float(n), Rgb(float(colour)), 0.5f));
  const Scene scene(std::move(desc));
  const WhittedIntegrator whitted(60);
  IndependentSampler sampler(0);
  RayCounters counters;
  const RadianceSample L = whitted.li(scene, Ray{Vec3(0, 0, 2), Vec3(0, 0, -1)}, sampler, counters);
  const double R = ((n - 1) / (n + 1)) * ((n - 1) / (n + 1));
  const double a = std::exp(std::log(colour) / 0.5 * d);
  EXPECT_NEAR(L.radiance.x, le * (1 - R) * (1 - R) * a / (1 - R * R * a * a), 1e-5 * le);
  EXPECT_EQ(L.alpha, 1.0f);
}

TEST(Whitted, FurnaceOfPureEmission) {
  SceneDesc desc;
  test::add_sphere(desc, Vec3(0.2f, 0.1f, 0), 3.0f, test::add_material(desc, Rgb(0.0f), Rgb(1.0f), true));
  const Scene scene(std::move(desc));
  CameraDesc cam;
  RenderSettings settings;
  settings.width = settings.height = 8;
  settings.spp = 4;
  Film film(8, 8);
  render(scene, Camera(cam, 8, 8), WhittedIntegrator(8), settings, film);
  for (float v : film.resolve_rgba()) EXPECT_EQ(v, 1.0f);
}

// Point and spot lights over a Lambertian floor and wall, with a mirror sphere, a glass sphere
// and a smooth plastic block.
SceneDesc specular_scene() {
  SceneDesc desc;
  const int floor = test::add_material(desc, Rgb(0.6f, 0.55f, 0.5f));
  test::add_quad(desc, Vec3(-3, -3, 0), Vec3(6, 0, 0), Vec3(0, 6, 0), floor);
  test::add_quad(desc, Vec3(-3, 2, 0), Vec3(6, 0, 0), Vec3(0, 0, 3), test::add_material(desc, Rgb(0.3f, 0.5f, 0.7f)));
  MaterialDesc mirror;
  mirror.metallic = 1;
  mirror.roughness = 0;
  mirror.base_color = Rgb(0.9f, 0.8f, 0.6f);
  desc.materials.push_back(mirror);
  test::add_sphere(desc, Vec3(-0.8f, 0.5f, 0.6f), 0.6f, int(desc.materials.size()) - 1);
  test::add_sphere(desc, Vec3(0.7f, -0.2f, 0.5f), 0.5f, test::add_glass(desc, 1.5f, Rgb(0.8f, 0.9f, 1.0f), 0.5f));
  MaterialDesc plastic;
  plastic.metallic = 0;
  plastic.roughness = 0;
  plastic.base_color = Rgb(0.7f, 0.2f, 0.2f);
  desc.materials.push_back(plastic);
  test::add_box(desc, Vec3(0.2f, 0.8f, 0), Vec3(1.0f, 1.4f, 0.7f), int(desc.materials.size()) - 1);
  PunctualLightDesc point;
  point.position = Vec3(0.5f, -1.5f, 2.5f);
  point.intensity = Rgb(6.0f, 6.0f, 5.0f);
  desc.lights.push_back(point);
  PunctualLightDesc spot;
  spot.type = LightType::Spot;
  spot.position = Vec3(-2, -1, 2);
  spot.direction = normalize(Vec3(1.5f, 1.2f, -2));
  spot.intensity = Rgb(4.0f, 3.0f, 2.0f);
  spot.cos_inner = std::cos(0.3f);
  spot.cos_outer = std::cos(0.6f);
  desc.lights.push_back(spot);
  return desc;
}

TEST(Whitted, AgreesWithThePathTracerLitOnlyDirectly) {
  const Scene scene(specular_scene());
  CameraDesc cam;
  cam.camera_to_world = Transform::look_at(Vec3(0.2f, -4, 2.2f), Vec3(0, 0.3f, 0.5f), Vec3(0, 0, 1));
  cam.yfov = 0.8f;
  RenderSettings settings;
  settings.width = 32;
  settings.height = 24;
  settings.max_depth = 12;
  settings.max_diffuse_depth = 0;  // Whitted lights diffuse surfaces directly only
  // The seed-swap test below models pixel errors as independent Monte Carlo noise; stratified samplers
  // leave a few large errors at edges and many tiny ones, which that model does not describe.
  settings.sampler = "independent";
  const Camera camera(cam, settings.width, settings.height);
  const WhittedIntegrator whitted(settings.max_depth);
  const PathIntegrator path(settings.max_depth, settings.rr_start_depth, settings.max_diffuse_depth);
  std::vector<float> w[2], p[2];
  for (int seed = 0; seed < 2; ++seed) {
    settings.seed = uint64_t(seed);
    Film fw(settings.width, settings.height), fp(settings.width, settings.height);
    settings.spp = 16;
    render(scene, camera, whitted, settings, fw);
    settings.spp = 1024;
    const RenderStats stats = render(scene, camera, path, settings, fp);
    EXPECT_EQ(stats.nonfinite_samples, 0u);
    w[seed] = fw.resolve_rgba();
    p[seed] = fp.resolve_rgba();
  }
  // As in Glass.IndexOneIsInvisible: differences between integrators must be no larger than
  // differences between seeds.
  test::SeedSwapTest swap;
  double mean_w = 0, mean_p = 0;
  size_t n = 0;
  for (size_t i = 0; i < w[0].size(); i += 4)
    for (int c = 0; c < 3; ++c, ++n) {
      swap.add(w[0][i + c], w[1][i + c], p[0][i + c], p[1][i + c]);
      mean_w += w[0][i + c];
      mean_p += p[0][i + c];
    }
  ASSERT_GT(mean_w, 0.0);
  EXPECT_LT(std::log(swap.ratio()), test::kSigmas * swap.log_ratio_sigma())
      << "image means: whitted " << mean_w / double(n) << ", path " << mean_p / double(n);
  // A bias of one sign over many pixels shows in the mean difference long before in the ratio.
  for (int c = 0; c < 3; ++c) {
    test::RunningStats diff;
    for (size_t i = 0; i < w[0].size(); i += 4) diff.add(double(w[0][i + c]) - p[1][i + c]);
    EXPECT_NEAR(diff.mean(), 0.0, test::kSigmas * diff.standard_error()) << "channel " << c;
  }
}

}  // namespace
}  // namespace prism
