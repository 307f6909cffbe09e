// Packet queries (Scene::intersect_packet / occluded_packet) answer exactly what the one-ray
// queries answer, lane by lane, through every kind of geometry and callback prism gives Embree:
// baked and instanced meshes, spheres (user geometry), alpha MASK and BLEND filters, and rays that
// skip the triangle they leave.
#include <gtest/gtest.h>

#include <vector>

#include "core/pcg32.h"
#include "core/sobol_sampler.h"
#include "integrators/path_integrator.h"
#include "core/sampling.h"
#include "core/scene.h"
#include "core/spawn.h"
#include "materials/material_eval.h"
#include "scene_builders.h"

namespace prism {
namespace {

SceneDesc packet_test_scene() {
  SceneDesc desc;
  const int wall = test::add_material(desc, Rgb(0.5f));
  test::add_inward_box(desc, Vec3(-2), Vec3(2), wall);
  // One mesh placed twice: instanced, not baked.
  const int block = test::add_box(desc, Vec3(-0.3f), Vec3(0.3f), test::add_material(desc, Rgb(0.3f)));
  desc.instances[size_t(block)].object_to_world = Transform::translate(Vec3(-1, -1, 0));
  InstanceDesc second;
  second.mesh = block;
  second.object_to_world = Transform::translate(Vec3(1, -1, 0.5f)) * Transform::rotate_quaternion(0, 0.38268343, 0, 0.92387953);
  desc.instances.push_back(second);
  // A 50%-opaque BLEND sheet and a sphere behind MASK (cut out) and BLEND alpha.
  const int blend = test::add_material(desc, Rgb(0.2f));
  desc.materials[size_t(blend)].base_alpha = 0.5f;
  desc.materials[size_t(blend)].alpha_mode = MaterialDesc::AlphaMode::Blend;
  test::add_quad(desc, Vec3(-1.5f, 0.5f, -1.5f), Vec3(3, 0, 0), Vec3(0, 0, 3), blend);
  const int masked = test::add_material(desc, Rgb(0.7f));
  desc.materials[size_t(masked)].base_alpha = 0.2f;
  desc.materials[size_t(masked)].alpha_mode = MaterialDesc::AlphaMode::Mask;
  test::add_sphere(desc, Vec3(0.8f, 1.2f, -0.8f), 0.4f, masked);
  test::add_sphere(desc, Vec3(-0.8f, 1.2f, 0.8f), 0.5f, blend);
  test::add_sphere(desc, Vec3(0, -1.2f, -1), 0.5f, wall);
  return desc;
}

void expect_same_hit(const SurfaceHit& a, const SurfaceHit& b) {
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.p, b.p);
  EXPECT_EQ(a.ng, b.ng);
  EXPECT_EQ(a.material, b.material);
  EXPECT_EQ(a.object, b.object);
  EXPECT_EQ(a.triangle.instance, b.triangle.instance);
  EXPECT_EQ(a.triangle.geometry, b.triangle.geometry);
  EXPECT_EQ(a.triangle.primitive, b.triangle.primitive);
}

TEST(PacketQueries, AgreeWithSingleRaysLaneByLane) {
  const Scene scene(packet_test_scene(), &material_alpha);
  Pcg32 rng(21, 22);
  int hits_compared = 0, spawned = 0, blocked = 0;
  for (int round = 0; round < 400; ++round) {
    // Packets of every width, and runs of rays longer than a packet (traced as several), of
    // camera-like rays from inside the box and the rays spawned from their hits (which skip the
    // triangle they leave) and shadow rays between two hits.
    constexpr int kMaxRays = 2 * Scene::kPacketSize + 3;
    const int n = 1 + round % kMaxRays;
    Ray rays[kMaxRays], next[kMaxRays], shadow[kMaxRays];
    for (int k = 0; k < n; ++k)
      rays[k] = Ray{Vec3(3.6f * rng.next_float() - 1.8f, 3.6f * rng.next_float() - 1.8f, 1.9f),
                    sample_uniform_sphere({rng.next_float(), rng.next_float()})};
    SurfaceHit hits[kMaxRays];
    bool found[kMaxRays];
    scene.intersect_packet(rays, n, hits, found, round % 2 == 0);
    for (int k = 0; k < n; ++k) {
      SurfaceHit single;
      ASSERT_EQ(found[k], scene.intersect(rays[k], single)) << "round " << round << " lane " << k;
      next[k] = rays[k];
      shadow[k] = rays[k];
      if (!found[k]) continue;
      expect_same_hit(hits[k], single);
      ++hits_compared;
      const Vec3 n_side = dot(hits[k].ng, rays[k].dir) < 0 ? hits[k].ng : -hits[k].ng;
      next[k] = spawn_ray(hits[k], normalize(n_side + sample_uniform_sphere({rng.next_float(), rng.next_float()})));
      shadow[k] = spawn_ray_between(hits[k], Vec3(0, 1.9f, 0), Vec3(0.0f), Vec3(0, -1, 0));
      spawned += next[k].leaves.valid();
    }
    SurfaceHit next_hits[kMaxRays];
    bool next_found[kMaxRays], occluded[kMaxRays];
    scene.intersect_packet(next, n, next_hits, next_found);
    scene.occluded_packet(shadow, n, occluded);
    for (int k = 0; k < n; ++k) {
      SurfaceHit single;
      ASSERT_EQ(next_found[k], scene.intersect(next[k], single)) << "round " << round << " lane " << k;
      if (next_found[k]) expect_same_hit(next_hits[k], single);
      EXPECT_EQ(occluded[k], scene.occluded(shadow[k])) << "round " << round << " lane " << k;
      blocked += occluded[k];
    }
  }
  // The rays did exercise what they were meant to.
  EXPECT_GT(hits_compared, 1000);
  EXPECT_GT(spawned, 1000);
  EXPECT_GT(blocked, 100);
}

// Every lane of a packet of paths traced in lockstep must come out exactly as the same path traced
// alone, AOVs included.
void expect_paths_in_lockstep_match_paths_alone(const Scene& scene) {
  const PathIntegrator path(8, 3);
  Pcg32 rng(31, 32);
  RayCounters packed_counters, alone_counters;
  constexpr int kMaxPaths = 2 * Scene::kPacketSize + 3;  // more than a packet: traced eight at a time
  for (int round = 0; round < 300; ++round) {
    const int n = 1 + round % kMaxPaths;
    Ray rays[kMaxPaths];
    std::vector<SobolSampler> lane_samplers(kMaxPaths, SobolSampler(5));
    Sampler* samplers[kMaxPaths];
    AovSample aov[kMaxPaths];
    AovSample* aovs[kMaxPaths];
    for (int k = 0; k < n; ++k) {
      rays[k] = Ray{Vec3(3.6f * rng.next_float() - 1.8f, 3.6f * rng.next_float() - 1.8f, 1.9f),
                    sample_uniform_sphere({rng.next_float(), rng.next_float()})};
      lane_samplers[k].start_pixel_sample(round, 0, uint64_t(k));
      samplers[k] = &lane_samplers[k];
      aovs[k] = &aov[k];
    }
    RadianceSample out[kMaxPaths];
    path.li_packet(scene, rays, samplers, n, packed_counters, aovs, out);
    for (int k = 0; k < n; ++k) {
      SobolSampler alone_sampler(5);
      alone_sampler.start_pixel_sample(round, 0, uint64_t(k));
      AovSample alone_aov;
      const RadianceSample alone = path.li(scene, rays[k], alone_sampler, alone_counters, &alone_aov);
      ASSERT_EQ(out[k].radiance, alone.radiance) << "round " << round << " lane " << k;
      EXPECT_EQ(out[k].alpha, alone.alpha);
      EXPECT_EQ(aov[k].direct, alone_aov.direct);
      EXPECT_EQ(aov[k].indirect, alone_aov.indirect);
      EXPECT_EQ(aov[k].emission, alone_aov.emission);
      EXPECT_EQ(aov[k].normal, alone_aov.normal);
      EXPECT_EQ(aov[k].object, alone_aov.object);
    }
  }
  EXPECT_EQ(packed_counters.camera, alone_counters.camera);
  EXPECT_EQ(packed_counters.extension, alone_counters.extension);
  EXPECT_EQ(packed_counters.shadow, alone_counters.shadow);
  EXPECT_GT(packed_counters.shadow, 1000u);
  EXPECT_GT(packed_counters.extension, 1000u);
}

// Paths in lockstep through glass with absorption (a medium stack), alpha, spheres, an emitter and
// instanced meshes.
SceneDesc lockstep_test_scene() {
  SceneDesc desc = packet_test_scene();
  const int glass = test::add_glass(desc, 1.5f, Rgb(0.6f, 0.8f, 0.9f));
  test::add_sphere(desc, Vec3(0.6f, 0, 0.6f), 0.4f, glass);
  test::add_box(desc, Vec3(-1.2f, 0.2f, 0.9f), Vec3(-0.6f, 0.8f, 1.5f), glass);
  return desc;
}

TEST(PacketQueries, PathsInLockstepMatchPathsAlone) {
  SceneDesc desc = lockstep_test_scene();
  const int light = test::add_material(desc, Rgb(0.0f), Rgb(8.0f));
  test::add_quad(desc, Vec3(-0.5f, 1.99f, -0.5f), Vec3(1, 0, 0), Vec3(0, 0, 1), light);  // facing down
  const Scene scene(std::move(desc), &material_alpha);
  ASSERT_FALSE(scene.emitters().picks_ahead());
  expect_paths_in_lockstep_match_paths_alone(scene);
}

// The same under a light tree larger than the caches, where the lanes choose their lights together
// (Emitters::pick_many): a ceiling of 80,000 small emissive triangles, none sharing an edge (so each
// is a light of its own), in four colours.
TEST(PacketQueries, PathsInLockstepMatchPathsAloneUnderALargeLightTree) {
  SceneDesc desc = lockstep_test_scene();
  int lamp[4];
  for (int k = 0; k < 4; ++k) lamp[k] = test::add_material(desc, Rgb(0.0f), Rgb(2.0f + float(k), 3.0f, 4.0f - float(k)));
  constexpr int kSide = 284;
  PrimitiveDesc ceiling[4];
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      PrimitiveDesc& prim = ceiling[(x + 2 * y) % 4];
      const float cell = 3.8f / kSide;
      const Vec3 c(-1.9f + cell * float(x), 1.98f, -1.9f + cell * float(y));
      const uint32_t first = uint32_t(prim.positions.size());
      prim.positions.insert(prim.positions.end(), {c, c + Vec3(0.8f * cell, 0, 0), c + Vec3(0, 0, 0.8f * cell)});
      prim.indices.insert(prim.indices.end(), {first, first + 1, first + 2});  // facing down
    }
  for (int k = 0; k < 4; ++k) {
    ceiling[k].material = lamp[k];
    test::add_mesh(desc, std::move(ceiling[k]));
  }
  const Scene scene(std::move(desc), &material_alpha);
  ASSERT_EQ(scene.emitters().size(), size_t(kSide) * kSide);
  ASSERT_TRUE(scene.emitters().picks_ahead()) << scene.emitters().tree().node_bytes() << " bytes of nodes";
  expect_paths_in_lockstep_match_paths_alone(scene);
}

}  // namespace
}  // namespace prism
