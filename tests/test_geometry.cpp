// Ray queries: sphere and triangle hits, transforms and instancing, and spawned rays that never re-hit.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/frame.h"
#include "core/pcg32.h"
#include "core/sampling.h"
#include "core/scene.h"
#include "core/spawn.h"
#include "core/sphere_geometry.h"
#include "core/transform.h"
#include "scene_builders.h"

namespace prism {
namespace {

TEST(SphereIntersection, ExactDistanceAcrossScales) {
  for (float r : {1e-4f, 1e-2f, 1.0f, 1e3f, 1e5f}) {
    for (float dist : {3.0f, 1e3f, 1e5f}) {
      const Vec3 c(0.3f * r, -0.2f * r, dist * r);
      Ray ray{Vec3(0.3f * r, -0.2f * r, 0), Vec3(0, 0, 1)};
      const double t = intersect_sphere(c, r, ray);
      const double expected = double(c.z) - r;
      EXPECT_NEAR(t, expected, 1e-6 * expected + 1e-7 * r) << "r " << r << " dist " << dist;
    }
  }
}

TEST(SphereIntersection, FromInsideHitsFarSide) {
  Ray ray{Vec3(0, 0, 0), Vec3(1, 0, 0)};
  EXPECT_NEAR(intersect_sphere(Vec3(0.5f, 0, 0), 2.0f, ray), 2.5, 1e-6);
  ray.t_max = 2.0f;
  EXPECT_LT(intersect_sphere(Vec3(0.5f, 0, 0), 2.0f, ray), 0.0);
}

TEST(SphereIntersection, GrazingAndMiss) {
  const Ray miss{Vec3(0, 1.0001f, -5), Vec3(0, 0, 1)};
  EXPECT_LT(intersect_sphere(Vec3(0, 0, 0), 1.0f, miss), 0.0);
  const Ray graze{Vec3(0, 0.9999f, -5), Vec3(0, 0, 1)};
  const double t = intersect_sphere(Vec3(0, 0, 0), 1.0f, graze);
  EXPECT_NEAR(t, 5.0 - std::sqrt(1.0 - 0.9999 * 0.9999), 1e-5);
}

// The spawn offsets' float stepping must be std::nextafter's, including at signed zeros,
// denormals, the largest finite floats, infinities and NaN, and across random bit patterns.
TEST(SpawnOffsets, FloatStepsMatchNextafter) {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> values = {0.0f,  -0.0f, std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::denorm_min(),
                               1.0f,  -1.0f, std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                               inf,   -inf,  std::numeric_limits<float>::min(), -std::numeric_limits<float>::min()};
  Pcg32 rng(7, 1);
  for (int i = 0; i < 100000; ++i) values.push_back(std::bit_cast<float>(rng.next_u32()));
  for (float v : values) {
    if (std::isnan(v)) {
      EXPECT_TRUE(std::isnan(next_float_up(v)));
      EXPECT_TRUE(std::isnan(next_float_down(v)));
      continue;
    }
    EXPECT_EQ(std::bit_cast<uint32_t>(next_float_up(v)), std::bit_cast<uint32_t>(std::nextafter(v, inf))) << v;
    EXPECT_EQ(std::bit_cast<uint32_t>(next_float_down(v)), std::bit_cast<uint32_t>(std::nextafter(v, -inf))) << v;
  }
}

TEST(SceneHits, SphereHitHasOutwardNormalAndExactPoint) {
  SceneDesc desc;
  const int m = test::add_material(desc, Rgb(0.5f));
  test::add_sphere(desc, Vec3(1, 2, 3), 0.5f, m);
  const Scene scene(std::move(desc));
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect(Ray{Vec3(1, 2, 10) - scene.origin(), Vec3(0, 0, -1)}, hit));
  EXPECT_NEAR(hit.t, 6.5f, 1e-5f);
  EXPECT_NEAR(hit.p.z + scene.origin().z, 3.5f, 1e-6f);  // the scene is moved to its own centre
  EXPECT_NEAR(hit.ng.z, 1.0f, 1e-6f);
  EXPECT_EQ(hit.material, m);
  EXPECT_EQ(hit.emitter, -1);
}

TEST(SceneHits, TriangleHitInterpolatesAttributes) {
  SceneDesc desc;
  const int m = test::add_material(desc, Rgb(0.5f));
  test::add_quad(desc, Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 4, 0), m);
  const Scene scene(std::move(desc));
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect(Ray{Vec3(0.5f, 1.0f, 5), Vec3(0, 0, -1)}, hit));
  EXPECT_NEAR(hit.t, 5.0f, 1e-6f);
  EXPECT_NEAR(hit.p.x, 0.5f, 1e-6f);
  EXPECT_NEAR(hit.p.y, 1.0f, 1e-6f);
  EXPECT_NEAR(hit.uv.x, 0.25f, 1e-6f);
  EXPECT_NEAR(hit.uv.y, 0.25f, 1e-6f);
  EXPECT_NEAR(hit.ng.z, 1.0f, 1e-6f);  // cross(u, v) = +z
  EXPECT_FALSE(scene.intersect(Ray{Vec3(2.5f, 1.0f, 5), Vec3(0, 0, -1)}, hit));
}

TEST(SceneHits, InstancedMeshIsSharedAndTransformed) {
  SceneDesc desc;
  const int m = test::add_material(desc, Rgb(0.5f));
  const int mesh = test::add_quad(desc, Vec3(-1, -1, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), m);
  // A second placement of the same mesh: moved, rotated a quarter turn about x, scaled by 3.
  InstanceDesc second;
  second.mesh = mesh;
  second.object_to_world = Transform::translate(Vec3(10, 0, 0)) * Transform::rotate_quaternion(std::sin(0.25 * M_PI), 0, 0, std::cos(0.25 * M_PI)) *
                           Transform::scale(Vec3(3.0f));
  desc.instances.push_back(second);
  EXPECT_TRUE(desc.features().instancing);
  EXPECT_EQ(desc.meshes.size(), 1u);
  EXPECT_EQ(desc.triangle_count(), 4u);
  const Scene scene(std::move(desc));
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect(Ray{Vec3(0.5f, 0.5f, 5), Vec3(0, 0, -1)}, hit));
  EXPECT_NEAR(hit.p.z, 0.0f, 1e-6f);
  // The rotated copy lies in the plane y = 0, spanning x in [7, 13] and z in [-3, 3]; its front
  // (+z rotated by +90 degrees about x) faces -y.
  ASSERT_TRUE(scene.intersect(Ray{Vec3(12, 5, 2), Vec3(0, -1, 0)}, hit));
  EXPECT_NEAR(hit.t, 5.0f, 1e-5f);
  EXPECT_NEAR(hit.p.x, 12.0f, 1e-5f);
  EXPECT_NEAR(hit.p.z, 2.0f, 1e-5f);
  EXPECT_NEAR(hit.ng.y, -1.0f, 1e-5f);
  EXPECT_NEAR(hit.uv.x, (12.0f - 7.0f) / 6.0f, 1e-5f);
  EXPECT_FALSE(scene.intersect(Ray{Vec3(13.5f, 5, 2), Vec3(0, -1, 0)}, hit));
}

// A ray that names the triangle it leaves never hits it, and still hits everything else: the
// same quad placed twice (instanced) and a quad baked into world space, each crossed by a ray
// starting just above its plane, as if the offset had gone the wrong way, and passing on down.
TEST(SceneHits, RaysNeverHitTheTriangleTheyLeave) {
  SceneDesc desc;
  const int m = test::add_material(desc, Rgb(0.5f));
  const int shared = test::add_quad(desc, Vec3(-1, -1, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), m);
  desc.instances.push_back({"above", shared, Transform::translate(Vec3(0, 0, 1))});
  test::add_quad(desc, Vec3(-1, -1, 2), Vec3(2, 0, 0), Vec3(0, 2, 0), m);  // baked: used once
  const Scene scene(std::move(desc));
  for (float z : {0.0f, 1.0f, 2.0f}) {
    SurfaceHit on;
    ASSERT_TRUE(scene.intersect(Ray{Vec3(0.3f, 0.2f, z + 0.5f), Vec3(0, 0, -1)}, on));
    ASSERT_TRUE(on.triangle.valid());
    EXPECT_EQ(on.triangle.instance == TriangleId::kNone, z == 2.0f) << z;  // only the shared mesh is instanced
    Ray down(on.p + Vec3(0, 0, 1e-3f), Vec3(0, 0, -1), 0.0f, INFINITY, on.triangle);
    SurfaceHit next;
    const bool hits_below = scene.intersect(down, next);
    EXPECT_EQ(hits_below, z > 0.0f) << z;
    if (hits_below) {
      EXPECT_FLOAT_EQ(next.p.z, z - 1.0f);
    }
    EXPECT_EQ(scene.occluded(down), z > 0.0f) << z;
    down.leaves = {};
    ASSERT_TRUE(scene.intersect(down, next)) << z;  // without the name, its own plane is met
    EXPECT_FLOAT_EQ(next.p.z, z);
  }
}

TEST(SceneHits, MirroredInstanceKeepsFrontFaceByDeterminant) {
  // glTF 2.0 §3.7.4: a negative determinant makes clockwise faces front-facing, so the
  // geometric normal follows the mirrored surface rather than the flipped winding.
  SceneDesc desc;
  const int m = test::add_material(desc, Rgb(0.5f));
  test::add_quad(desc, Vec3(-1, -1, 1), Vec3(2, 0, 0), Vec3(0, 2, 0), m, Transform::scale(Vec3(-1, 1, 1)));
  const Scene scene(std::move(desc));
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect(Ray{Vec3(0.2f, 0.1f, 5), Vec3(0, 0, -1)}, hit));
  EXPECT_NEAR(hit.ng.z, 1.0f, 1e-6f);
}

TEST(SceneHits, EmissiveInstancesAreEmitters) {
  SceneDesc desc;
  const int light = test::add_material(desc, Rgb(0.0f), Rgb(1.0f));
  const int mesh = test::add_quad(desc, Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), light);
  desc.instances.push_back({"copy", mesh, Transform::translate(Vec3(5, 0, 0))});
  const Scene scene(std::move(desc));
  EXPECT_EQ(scene.emitters().size(), 2u);  // a quad each
  SurfaceHit a, b;
  ASSERT_TRUE(scene.intersect(Ray{Vec3(0.5f, 0.2f, 1), Vec3(0, 0, -1)}, a));
  ASSERT_TRUE(scene.intersect(Ray{Vec3(5.5f, 0.2f, 1), Vec3(0, 0, -1)}, b));
  EXPECT_GE(a.emitter, 0);
  EXPECT_GE(b.emitter, 0);
  EXPECT_NE(a.emitter, b.emitter);
  EXPECT_FLOAT_EQ(scene.emitters().power_pick_probability(a.emitter), 0.5f);
}

TEST(SceneValidation, RejectsOutOfRangeIndices) {
  SceneDesc desc;
  desc.source = "test";
  test::add_quad(desc, Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), -1);
  desc.meshes[0].primitives[0].indices[2] = 99;
  EXPECT_THROW(Scene{std::move(desc)}, std::invalid_argument);
}

TEST(Transform, ComposeAndInvert) {
  const Transform a = Transform::translate(Vec3(1, 2, 3)) * Transform::rotate_quaternion(0.1, 0.7, -0.2, 0.6) *
                      Transform::scale(Vec3(2, 3, 0.5f));
  const Vec3 p(0.3f, -1.2f, 4.0f);
  const Vec3 q = a.inverse().point(a.point(p));
  EXPECT_NEAR(q.x, p.x, 1e-5f);
  EXPECT_NEAR(q.y, p.y, 1e-5f);
  EXPECT_NEAR(q.z, p.z, 1e-5f);
  // Normals stay perpendicular to transformed tangents.
  const Vec3 t(1, 0, 0), n(0, 0, 1);
  EXPECT_NEAR(dot(a.vector(t), a.normal(n)), 0.0f, 1e-5f);
  EXPECT_FALSE(Transform::scale(Vec3(1, 0, 1)).is_invertible());
  EXPECT_TRUE(Transform::scale(Vec3(-1, 1, 1)).flips_handedness());
}

// Rays spawned off a surface toward its front never hit that surface again, and rays spawned
// into a closed sphere reach its far side, at every scale.
TEST(SpawnedRays, NeverReHitTheirOwnSurface) {
  Pcg32 rng(11, 12);
  for (float scale : {1e-4f, 1e-2f, 1.0f, 1e2f, 1e4f}) {
    for (float offset : {0.0f, 1e3f}) {
      SceneDesc desc;
      const int m = test::add_material(desc, Rgb(0.5f));
      const Vec3 origin = Vec3(offset * scale, -offset * scale, 0.5f * offset * scale);
      // A sliver triangle pair and a sphere, both around `origin`.
      test::add_quad(desc, origin + Vec3(-1, -1e-3f, 0) * scale, Vec3(2, 0, 0) * scale, Vec3(0.5f, 2e-3f, 0.3f) * scale, m);
      test::add_sphere(desc, origin + Vec3(0, 0, 5) * scale, 1.0f * scale, m);
      // A speck on the far side keeps the scene's centre at 0, so it stays where it is (not moved to
      // a render origin) and the hits really are offset * scale from the origin.
      if (offset > 0) test::add_sphere(desc, -origin, 1e-3f * scale, m);
      const Scene scene(std::move(desc));
      ASSERT_EQ(scene.origin(), Vec3(0.0f));
      int failures = 0, hits = 0;
      for (int i = 0; i < 2000; ++i) {
        // Find a point on each surface by casting at it, then leave in a random direction.
        const bool sphere = i % 2;
        const Vec3 target = sphere ? origin + Vec3(0, 0, 5) * scale : origin + Vec3(rng.next_float() - 0.5f, 0, 0) * scale;
        const Vec3 from = target + sample_uniform_sphere({rng.next_float(), rng.next_float()}) * (3.0f * scale);
        SurfaceHit hit;
        if (!scene.intersect(Ray{from, target - from}, hit)) continue;
        ++hits;
        const Vec3 out_dir = face_forward(hit.ng, from - hit.p);
        Vec3 w = sample_cosine_hemisphere({rng.next_float(), rng.next_float()});
        const Frame f = Frame::from_normal(out_dir);
        w = f.to_world(w);
        SurfaceHit again;
        const Ray leave = spawn_ray(hit, w);
        if (scene.intersect(leave, again) && again.t < 1e-3f * scale) ++failures;
        if (sphere && dot(out_dir, hit.ng) > 0) {
          // Into the sphere: must reach the far side, not the entry point.
          const Ray into = spawn_ray(hit, -w);
          ASSERT_TRUE(scene.intersect(into, again)) << "scale " << scale;
          if (again.t < 1e-3f * scale) ++failures;
        }
      }
      EXPECT_GT(hits, 1000) << "scale " << scale << " offset " << offset;
      EXPECT_EQ(failures, 0) << "scale " << scale << " offset " << offset;
    }
  }
}

}  // namespace
}  // namespace prism
