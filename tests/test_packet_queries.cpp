// Packet queries (Scene::intersect_packet / occluded_packet) answer exactly what the one-ray
// queries answer, lane by lane, through every kind of geometry and callback prism gives Embree:
// baked and instanced meshes, spheres (user geometry), alpha MASK and BLEND filters, and rays that
// skip the triangle they leave.
#include <gtest/gtest.h>

#include "core/pcg32.h"
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
    // Packets of every width, of camera-like rays from inside the box and the rays spawned from
    // their hits (which skip the triangle they leave) and shadow rays between two hits.
    const int n = 1 + round % Scene::kPacketSize;
    Ray rays[Scene::kPacketSize], next[Scene::kPacketSize], shadow[Scene::kPacketSize];
    for (int k = 0; k < n; ++k)
      rays[k] = Ray{Vec3(3.6f * rng.next_float() - 1.8f, 3.6f * rng.next_float() - 1.8f, 1.9f),
                    sample_uniform_sphere({rng.next_float(), rng.next_float()})};
    SurfaceHit hits[Scene::kPacketSize];
    bool found[Scene::kPacketSize];
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
    SurfaceHit next_hits[Scene::kPacketSize];
    bool next_found[Scene::kPacketSize], occluded[Scene::kPacketSize];
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

}  // namespace
}  // namespace prism
