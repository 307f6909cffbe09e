// Path splitting at the first vertex (PathIntegrator::set_split): the continuations draw a longer
// render's samples, keep every estimate's mean, and lower the error as independent samples of the
// light past the first vertex must.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/renderer.h"
#include "core/sampler_factory.h"
#include "core/scene.h"
#include "furnace_scene.h"
#include "integrators/path_integrator.h"
#include "io/gltf_loader.h"
#include "statistics.h"

namespace prism {
namespace {

constexpr int kNoRoulette = 1 << 20;

// A sampler that notes where it stands at each vertex's draws.
class RecordingSampler final : public Sampler {
 public:
  explicit RecordingSampler(uint64_t seed) : inner_(make_sampler("sobol", seed)) {}
  void start_pixel_sample(int x, int y, uint64_t index) override { inner_->start_pixel_sample(x, y, index); }
  float next_1d() override { return inner_->next_1d(); }
  Vec2 next_2d() override { return inner_->next_2d(); }
  SamplerPosition position() const override { return inner_->position(); }
  void move_to(const SamplerPosition& to) override { inner_->move_to(to); }
  void draw_vertex(VertexSamples& v) override {
    vertices.push_back(inner_->position());
    inner_->draw_vertex(v);
  }
  std::vector<SamplerPosition> vertices;

 private:
  std::unique_ptr<Sampler> inner_;
};

// Camera sample s of a pixel draws its first vertex's light sample at (s, the dimension after the
// camera's), and continuation c its first vertex's draws at (s * K + c, that dimension), then its
// next vertices' at the following dimensions of that index: the mapping that makes the
// continuations a longer render's samples.
TEST(PathSplitting, ContinuationsDrawSampleIndicesOfTheirOwn) {
  Diagnostics diag;
  SceneDesc desc = load_gltf(PRISM_SOURCE_DIR "/scenes/cornell-box/cornell-box.gltf", diag);
  const CameraDesc cam = desc.cameras.at(0);
  const Scene scene(std::move(desc));
  const Camera camera = Camera(cam, 16, 16).relative_to(scene.origin());  // rays in the scene's coordinates
  const int split = 3;
  PathIntegrator integrator(8, kNoRoulette);
  integrator.set_split(split);
  constexpr int kLanes = 5;
  std::vector<std::unique_ptr<RecordingSampler>> lanes;
  Sampler* samplers[kLanes];
  Ray rays[kLanes];
  for (int k = 0; k < kLanes; ++k) {
    lanes.push_back(std::make_unique<RecordingSampler>(3));
    samplers[k] = lanes.back().get();
    samplers[k]->start_pixel_sample(8, 8, uint64_t(7 + k));
    const Vec2 jitter = samplers[k]->next_2d();
    rays[k] = camera.generate_ray(8 + jitter.x, 8 + jitter.y);  // the back wall, in the middle
  }
  RayCounters counters;
  RadianceSample out[kLanes];
  integrator.li_packet(scene, rays, samplers, kLanes, counters, nullptr, out);
  EXPECT_EQ(counters.camera, uint64_t(kLanes));
  int bounces = 0;
  for (int k = 0; k < kLanes; ++k) {
    const std::vector<SamplerPosition>& v = lanes[size_t(k)]->vertices;
    const uint64_t s = uint64_t(7 + k);
    const uint32_t first = 1;  // after the jitter's one 2D draw
    ASSERT_FALSE(v.empty());
    EXPECT_EQ(v[0].index, s);
    EXPECT_EQ(v[0].dimension, first);
    size_t i = 1;
    for (int c = 0; c < split; ++c) {
      uint32_t vertex = 0;
      for (; i < v.size() && v[i].index == s * split + uint64_t(c); ++i, ++vertex)
        EXPECT_EQ(v[i].dimension, first + 5 * vertex) << "lane " << k << ", continuation " << c;
      EXPECT_GE(vertex, 1u) << "lane " << k << ", continuation " << c;
      bounces += int(vertex);
    }
    EXPECT_EQ(i, v.size()) << "lane " << k << ": draws at another index";
  }
  EXPECT_GT(bounces, kLanes * split * 2);  // paths went on past their first vertex
}

// The furnace's closed form with every sampler, two and three continuations (the mean of three is
// no power of two), with and without Russian roulette: the first vertex's light sample, taken by
// one continuation for all, must count as much as without splitting.
TEST(PathSplitting, TheFurnaceKeepsItsRadiance) {
  for (int split : {2, 3}) {
    test::expect_furnace(test::furnace_box(1.0, 0.5), test::furnace_camera(Vec3(0.1f)), 0.5, 5, kNoRoulette,
                         test::furnace_radiance(1.0, 0.5, 5), 0, split);
    test::expect_furnace(test::furnace_box(1.0, 0.8), test::furnace_camera(Vec3(0.0f)), 0.8, 12, 1,
                         test::furnace_radiance(1.0, 0.8, 12), 0, split);
  }
}

// The Cornell box (an area light: next-event estimation and MIS at every vertex) renders the same
// image split as not: over the pixels, whose errors are independent (each pixel draws its own
// scrambles), the mean difference between the two renders is within its standard error.
TEST(PathSplitting, TheCornellBoxIsTheSameImage) {
  Diagnostics diag;
  SceneDesc desc = load_gltf(PRISM_SOURCE_DIR "/scenes/cornell-box/cornell-box.gltf", diag);
  const CameraDesc cam = desc.cameras.at(0);
  const Scene scene(std::move(desc));
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.spp = 64;
  std::vector<float> images[2];
  for (int s = 0; s < 2; ++s) {
    PathIntegrator integrator(settings.max_depth, settings.rr_start_depth);
    integrator.set_split(s == 0 ? 1 : 4);
    settings.seed = uint64_t(10 + s);  // independent noise in the two
    Film film(settings.width, settings.height);
    render(scene, Camera(cam, settings.width, settings.height), integrator, settings, film);
    images[s] = film.resolve_rgba();
  }
  for (int c = 0; c < 3; ++c) {
    test::RunningStats difference, unsplit;
    for (size_t i = size_t(c); i < images[0].size(); i += 4) {
      difference.add(double(images[1][i]) - images[0][i]);
      unsplit.add(images[0][i]);
    }
    std::printf("channel %d: mean %.5f, split minus unsplit %.5f +- %.5f\n", c, unsplit.mean(), difference.mean(),
                difference.standard_error());
    EXPECT_LT(std::abs(difference.mean()), test::kSigmas * difference.standard_error()) << "channel " << c;
  }
}

// With independent samples a camera sample's variance is A + B, A from what it draws up to its
// first vertex's light sample and B from its continuation; K continuations make it A + B / K. The
// RMSE ratio must then lie between 1/sqrt(K) and 1, and below 1 by more than its spread: the
// continuations draw values of their own (in the furnace every bounce adds light, so B > 0).
TEST(PathSplitting, ContinuationsLowerTheErrorAsIndependentSamplesMust) {
  const int size = 40, spp = 8, split = 4;
  const auto [r1, s1] = test::rmse_with_error(test::furnace_errors("independent", spp, size, 3));
  const auto [rk, sk] = test::rmse_with_error(test::furnace_errors("independent", spp, size, 3, split));
  const double ratio = rk / r1;
  const double sigma = ratio * std::hypot(s1 / r1, sk / rk);
  std::printf("RMSE %.5f unsplit, %.5f in %d continuations: ratio %.3f +- %.3f\n", r1, rk, split, ratio, sigma);
  EXPECT_LT(ratio, 1 - test::kSigmas * sigma);
  EXPECT_GT(ratio, 1 / std::sqrt(double(split)) - test::kSigmas * sigma);
  // Sobol's continuations, a longer render's samples, must lower it too.
  const auto [q1, t1] = test::rmse_with_error(test::furnace_errors("sobol", spp, size, 3));
  const auto [qk, tk] = test::rmse_with_error(test::furnace_errors("sobol", spp, size, 3, split));
  std::printf("sobol: RMSE %.5f unsplit, %.5f in %d continuations\n", q1, qk, split);
  EXPECT_LT(qk, q1 - test::kSigmas * std::hypot(t1, tk));
}

}  // namespace
}  // namespace prism
