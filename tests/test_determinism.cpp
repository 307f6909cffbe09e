// Determinism: the same scene, settings and seed give the same bits for any thread count or tile
// size; the structures built in parallel (the light tree) are the same on any number of threads.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <bit>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/camera.h"
#include "core/light_tree.h"
#include "core/renderer.h"
#include "core/scene.h"
#include "integrators/path_integrator.h"
#include "io/gltf_loader.h"
#include "mixed_lights.h"

namespace prism {
namespace {

// The Cornell box rendered with `settings`' spp in passes of these many samples each (the renders
// a time budget or a checkpointed render make), paths split into `split` continuations.
std::vector<float> render_cornell(int threads, int tile, uint64_t seed, int split = 1,
                                  const std::vector<int>& passes = {8}) {
  Diagnostics diag;
  SceneDesc desc = load_gltf(PRISM_SOURCE_DIR "/scenes/cornell-box/cornell-box.gltf", diag);
  const CameraDesc cam = desc.cameras.at(0);
  const Scene scene(std::move(desc));
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.threads = threads;
  s.tile_size = tile;
  s.seed = seed;
  Film film(s.width, s.height);
  PathIntegrator integrator(s.max_depth, s.rr_start_depth);
  integrator.set_split(split);
  s.spp = 0;
  for (const int pass : passes) {
    s.spp += pass;  // the film's samples so far continue up to the new count
    const RenderStats stats = render(scene, Camera(cam, s.width, s.height), integrator, s, film);
    EXPECT_EQ(stats.samples, uint64_t(s.width) * s.height * pass);
    EXPECT_EQ(stats.rays.camera, stats.samples) << "one camera ray per sample, split or not";
    EXPECT_EQ(stats.nonfinite_samples, 0u);
  }
  return film.resolve_rgba();
}

TEST(Determinism, SameBitsForAnyThreadCountAndTileSize) {
  const std::vector<float> reference = render_cornell(1, 16, 7);
  EXPECT_EQ(render_cornell(2, 16, 7), reference);
  EXPECT_EQ(render_cornell(2, 5, 7), reference);
  EXPECT_EQ(render_cornell(3, 64, 7), reference);
  EXPECT_NE(render_cornell(2, 16, 8), reference);  // the seed matters
}

// Split paths draw each continuation from a sample index of its own (s * split + c): the bits do
// not depend on threads, tiles or how the samples fall into passes, and splitting changes them.
TEST(Determinism, SplitPathsGiveTheSameBitsOnAnyThreadCountAndInPasses) {
  const std::vector<float> reference = render_cornell(1, 16, 7, 3);
  EXPECT_EQ(render_cornell(2, 5, 7, 3), reference);
  EXPECT_EQ(render_cornell(2, 16, 7, 3, {3, 1, 4}), reference);
  EXPECT_NE(render_cornell(1, 16, 7, 2), reference);
  EXPECT_NE(render_cornell(1, 16, 7, 1), reference);
}

}  // namespace
// Above 65536 lights a node builds its two subtrees in parallel, each in a place fixed by the
// light counts: the tree (its depth, every pick and every pmf) must be the same on one thread as on
// many. A third of the lights repeat another's bounds, so some subtrees end early in a leaf of
// lights alike and leave gaps in the node array.
TEST(Determinism, LightTreeIsTheSameOnOneThreadAsOnMany) {
  Pcg32 rng(15, 16);
  std::vector<LightBounds> lights = mixed_lights(rng, 150000);
  for (size_t k = 2; k < lights.size(); k += 3) lights[k] = lights[k - 1];
  std::optional<LightTree> alone;
  tbb::task_arena(1).execute([&] { alone.emplace(lights); });
  const LightTree shared(lights);
  ASSERT_EQ(alone->depth(), shared.depth());
  const auto bits = [](float x) { return std::bit_cast<uint32_t>(x); };
  int picked = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p = random_in_box(rng, 7.0f);
    const Vec3 n = i % 4 == 0 ? Vec3() : random_direction(rng);
    const float u = rng.next_float();
    const std::optional<LightTree::Pick> a = alone->sample(p, n, u), b = shared.sample(p, n, u);
    ASSERT_EQ(a.has_value(), b.has_value()) << "point " << i;
    if (!a) continue;
    ++picked;
    ASSERT_EQ(a->item, b->item) << "point " << i;
    ASSERT_EQ(bits(a->pmf), bits(b->pmf)) << "point " << i;
    ASSERT_EQ(bits(a->remapped), bits(b->remapped)) << "point " << i;
    const int other = int(rng.next_u32() % lights.size());
    ASSERT_EQ(bits(alone->pmf(other, p, n)), bits(shared.pmf(other, p, n))) << "point " << i << ", light " << other;
  }
  EXPECT_GT(picked, 1000);
}

}  // namespace prism
