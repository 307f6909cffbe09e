// Determinism: the same scene, settings and seed give the same bits for any thread count or tile size.
#include <gtest/gtest.h>

#include "core/camera.h"
#include "core/renderer.h"
#include "core/scene.h"
#include "integrators/path_integrator.h"
#include "io/gltf_loader.h"

namespace prism {
namespace {

std::vector<float> render_cornell(int threads, int tile, uint64_t seed) {
  Diagnostics diag;
  SceneDesc desc = load_gltf(PRISM_SOURCE_DIR "/scenes/cornell-box/cornell-box.gltf", diag);
  const CameraDesc cam = desc.cameras.at(0);
  const Scene scene(std::move(desc));
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.spp = 8;
  s.threads = threads;
  s.tile_size = tile;
  s.seed = seed;
  Film film(s.width, s.height);
  const PathIntegrator integrator(s.max_depth, s.rr_start_depth);
  const RenderStats stats = render(scene, Camera(cam, s.width, s.height), integrator, s, film);
  EXPECT_EQ(stats.samples, uint64_t(s.width) * s.height * s.spp);
  EXPECT_EQ(stats.rays.camera, stats.samples);
  EXPECT_EQ(stats.nonfinite_samples, 0u);
  return film.resolve_rgba();
}

TEST(Determinism, SameBitsForAnyThreadCountAndTileSize) {
  const std::vector<float> reference = render_cornell(1, 16, 7);
  EXPECT_EQ(render_cornell(2, 16, 7), reference);
  EXPECT_EQ(render_cornell(2, 5, 7), reference);
  EXPECT_EQ(render_cornell(3, 64, 7), reference);
  EXPECT_NE(render_cornell(2, 16, 8), reference);  // the seed matters
}

}  // namespace
}  // namespace prism
