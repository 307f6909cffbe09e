// Self-intersection at the extremes: rays spawned from hits on tetrahedra of every shape (down to
// 1e-4 slivers) and on spheres, placed with hit coordinates log-uniform over 1e-6..1e6 and turned
// at random, never hit their own surface again and always reach the far side from inside.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <string>

#include "core/frame.h"
#include "core/pcg32.h"
#include "core/sampling.h"
#include "core/scene.h"
#include "core/spawn.h"
#include "scene_builders.h"

namespace prism {
namespace {

float log_uniform(Pcg32& rng, float lo_exp, float hi_exp) {
  return std::pow(10.0f, lo_exp + (hi_exp - lo_exp) * rng.next_float());
}

// How far the solid extends from p (on its surface, outward normal n_out) straight inward: where
// the line p - n_out t leaves the tetrahedron through another face's plane (in double).
double depth_below(const std::array<Vec3, 4>& tet, const Vec3& p, const Vec3& n_out) {
  const Vec3 centroid = (tet[0] + tet[1] + tet[2] + tet[3]) * 0.25f;
  double exit = INFINITY;
  for (int i = 0; i < 4; ++i) {
    const Vec3& a = tet[(i + 1) % 4];
    Vec3 n = normalize(cross(tet[(i + 2) % 4] - a, tet[(i + 3) % 4] - a));
    if (dot(n, a - centroid) < 0) n = -n;  // outward
    const double toward = -double(dot(n_out, n));
    if (toward <= 1e-6) continue;  // the own face, or one the line runs away from
    exit = std::min(exit, double(dot(a - p, n)) / toward);
  }
  return exit;
}

// A tetrahedron is convex and its faces are exactly planar in float whatever its vertices, so
// the expectations are exact: a ray leaving a face outward never meets the tetrahedron again,
// and a ray spawned inward always meets another face. Each trial: a regular tetrahedron of size s
// squashed by a1, a2 (log-uniform in 1e-4..1) along two axes, turned at random, centred at c with
// |c| log-uniform in 1e-6..1e6, and a speck at -c that keeps the scene where it is (a lone solid
// would be moved to a render origin at its own centre, the easy case). Its thinnest extent is
// kept above 2^-15 |c| (256 float spacings); offsets are 32 spacings, and a solid thinner than
// the offset cannot be entered (docs/NUMERICS.md).
struct SpawnCounts {
  int trials = 0, rays = 0, slivers = 0, rehit = 0, escaped = 0, same_face = 0, near_edges = 0, inward = 0;
  std::string first_failure;
};

SpawnCounts spawn_from_tetrahedra() {
  Pcg32 rng(2026, 11);
  SpawnCounts counts;
  auto& [trials, rays, slivers, rehit, escaped, same_face, near_edges, inward, first_failure] = counts;
  const std::array<Vec3, 4> regular = {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)};
  while (trials < 400) {
    const float distance = log_uniform(rng, -6, 6);
    const float s = distance * log_uniform(rng, -3, -0.5f);  // the speck at -c stays far outside
    const float a1 = log_uniform(rng, -4, 0), a2 = log_uniform(rng, -4, 0);
    if (s * std::min(a1, a2) < distance * 0x1p-15f) continue;
    ++trials;
    slivers += std::min(a1, a2) < 1e-3f;
    const Vec3 c = sample_uniform_sphere({rng.next_float(), rng.next_float()}) * distance;
    const Vec3 axis = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    const float half_angle = kPi * rng.next_float();
    const Transform place = Transform::translate(c) * Transform::rotate_quaternion(axis.x * std::sin(half_angle), axis.y * std::sin(half_angle),
                                                                                 axis.z * std::sin(half_angle), std::cos(half_angle));
    std::array<Vec3, 4> tet;
    for (int i = 0; i < 4; ++i) tet[i] = place.point(regular[i] * Vec3(0.5f * s, 0.5f * s * a1, 0.5f * s * a2));
    SceneDesc desc;
    const int m = test::add_material(desc, Rgb(0.5f));
    PrimitiveDesc prim;
    prim.material = m;
    prim.positions.assign(tet.begin(), tet.end());
    const Vec3 centroid = (tet[0] + tet[1] + tet[2] + tet[3]) * 0.25f;
    for (uint32_t i = 0; i < 4; ++i) {
      uint32_t a = (i + 1) % 4, b = (i + 2) % 4, cc = (i + 3) % 4;
      if (dot(cross(tet[b] - tet[a], tet[cc] - tet[a]), tet[a] - centroid) < 0) std::swap(b, cc);  // outward
      prim.indices.insert(prim.indices.end(), {a, b, cc});
    }
    test::add_mesh(desc, std::move(prim));
    test::add_sphere(desc, -c, 1e-3f * distance, m);
    const Scene scene(std::move(desc));
    EXPECT_EQ(scene.origin(), Vec3(0.0f));
    const float size = s;
    auto on_solid = [&](const SurfaceHit& h) { return length(h.p - c) < 2.0f * size; };
    for (int i = 0; i < 40; ++i) {
      // Aim at a random point inside the solid from outside it.
      float w[4], sum = 0;
      for (float& x : w) sum += (x = rng.next_float() + 1e-3f);
      const Vec3 target = (tet[0] * w[0] + tet[1] * w[1] + tet[2] * w[2] + tet[3] * w[3]) / sum;
      const Vec3 from = target + sample_uniform_sphere({rng.next_float(), rng.next_float()}) * (4.0f * size);
      SurfaceHit hit;
      if (!scene.intersect(Ray{from, normalize(target - from)}, hit) || !on_solid(hit)) continue;
      ++rays;
      const Vec3 out = dot(hit.ng, from - hit.p) > 0 ? hit.ng : -hit.ng;
      const Vec3 dir = Frame::from_normal(out).to_world(sample_cosine_hemisphere({rng.next_float(), rng.next_float()}));
      auto fail = [&](const std::string& what) {  // counts.: clang 14 cannot capture structured bindings
        if (counts.first_failure.empty())
          counts.first_failure = what + ": distance " + std::to_string(distance) + " size " + std::to_string(s) + " squash " +
                          std::to_string(a1) + ", " + std::to_string(a2);
      };
      SurfaceHit again;
      if (scene.intersect(spawn_ray(hit, dir), again) && on_solid(again)) {
        ++rehit;
        fail("an outward ray met the solid again");
      }
      // Near its edges a sliver's wedge is thinner than the offset itself, and the inward origin
      // can land past the opposite face (every renderer that offsets has this limit;
      // docs/NUMERICS.md): only hits where the solid is 4 offsets deep are held to crossing.
      if (depth_below(tet, hit.p, out) < 4.0 * length(hit.p_error)) {
        ++near_edges;
        continue;
      }
      ++inward;
      if (!scene.intersect(spawn_ray(hit, -dir), again) || !on_solid(again)) {
        ++escaped;
        fail("an inward ray escaped");
      } else if (std::abs(dot(again.p - hit.p, hit.ng)) < 2.0f * length(hit.p_error) && dot(again.ng, hit.ng) > 0.999999f) {
        // On the own plane, facing the same way: no other face of a convex solid can be.
        ++same_face;
        fail("an inward ray met its own face");
      }
    }
  }
  return counts;
}

TEST(SelfIntersectionExtremes, SpawnedRaysNeverReHitTheirSurfaceAndAlwaysCrossClosedSolids) {
  const SpawnCounts c = spawn_from_tetrahedra();
  std::printf("%d rays, %d inward, %d where the solid is under 4 offsets deep, %d trials with slivers under 1e-3\n",
              c.rays, c.inward, c.near_edges, c.slivers);
  EXPECT_EQ(c.rehit, 0) << c.first_failure;
  EXPECT_EQ(c.escaped, 0) << c.first_failure;
  EXPECT_GT(c.rays, 8000);
  EXPECT_GT(c.inward, 7000);  // few hits were left out as too shallow
  EXPECT_GT(c.slivers, 40);
}

// On needle-shaped tetrahedra (squashed to 3e-4 along two axes) 17 of 15805 inward rays met their
// own face again: Embree tests a needle through its float normal, tilted by the cross product's
// cancellation, and saw the face's plane on the wrong side of the offset origin. Spawned rays now
// skip the triangle they leave (core/scene.cpp, skip_left_triangle).
TEST(SelfIntersectionExtremes, InwardRaysNeverMeetTheirOwnFace) {
  const SpawnCounts c = spawn_from_tetrahedra();
  EXPECT_EQ(c.same_face, 0) << c.first_failure;
}

// Where a ray from inside a sphere leaves it, in long double: the far root of |o + t d - c| = r.
Vec3 exit_point(const Vec3& c, float r, const Ray& ray) {
  long double oc[3], b = 0, cc = 0, dd = 0;
  for (int i = 0; i < 3; ++i) {
    oc[i] = (long double)ray.origin[i] - c[i];
    b += oc[i] * ray.dir[i];
    cc += oc[i] * oc[i];
    dd += (long double)ray.dir[i] * ray.dir[i];
  }
  const long double t = (-b + std::sqrt(b * b - dd * (cc - (long double)r * r))) / dd;
  return Vec3(float(ray.origin.x + t * ray.dir.x), float(ray.origin.y + t * ray.dir.y), float(ray.origin.z + t * ray.dir.z));
}

// Spheres of radius 10^-3..10^-0.5 of their distance from the origin, that distance log-uniform
// in 1e-6..1e6 (a speck at -c keeps each where it is): a ray spawned outward never meets its
// sphere again; one spawned inward always meets it again where it really leaves it (the exact far
// root from its offset origin, to 4 offsets), unless the offset put its origin past the surface (a
// grazing chord shorter than the offset; none here).
TEST(SelfIntersectionExtremes, SpheresAreNeverMetAgainOutwardAndAlwaysCrossedInward) {
  Pcg32 rng(2026, 12);
  int rays = 0, rehit = 0, wrong_exit = 0, origin_outside = 0;
  std::string first_failure;
  for (int trial = 0; trial < 400; ++trial) {
    const float distance = log_uniform(rng, -6, 6);
    const float r = distance * log_uniform(rng, -3, -0.5f);
    const Vec3 c = sample_uniform_sphere({rng.next_float(), rng.next_float()}) * distance;
    SceneDesc desc;
    const int m = test::add_material(desc, Rgb(0.5f));
    test::add_sphere(desc, c, r, m);
    test::add_sphere(desc, -c, 1e-3f * r, m);
    const Scene scene(std::move(desc));
    ASSERT_EQ(scene.origin(), Vec3(0.0f));
    auto on_sphere = [&](const SurfaceHit& h) { return length(h.p - c) < 1.5f * r; };
    for (int i = 0; i < 40; ++i) {
      const Vec3 target = c + sample_uniform_sphere({rng.next_float(), rng.next_float()}) * (r * rng.next_float());
      const Vec3 from = target + sample_uniform_sphere({rng.next_float(), rng.next_float()}) * (4.0f * r);
      SurfaceHit hit;
      if (!scene.intersect(Ray{from, normalize(target - from)}, hit) || !on_sphere(hit)) continue;
      ++rays;
      const Vec3 dir = Frame::from_normal(hit.ng).to_world(sample_cosine_hemisphere({rng.next_float(), rng.next_float()}));
      auto fail = [&](const std::string& what) {
        if (first_failure.empty())
          first_failure = what + ": distance " + std::to_string(distance) + " radius " + std::to_string(r);
      };
      SurfaceHit again;
      if (scene.intersect(spawn_ray(hit, dir), again) && on_sphere(again)) {
        ++rehit;
        fail("an outward ray met its sphere again");
      }
      const Ray inward = spawn_ray(hit, -dir);
      if (length(inward.origin - c) >= r) {
        ++origin_outside;
        continue;
      }
      if (!scene.intersect(inward, again) || !on_sphere(again) ||
          length(again.p - exit_point(c, r, inward)) > 4 * length(hit.p_error)) {
        ++wrong_exit;
        fail("an inward ray did not leave where it should");
      }
    }
  }
  std::printf("%d rays, %d inward origins past the surface\n", rays, origin_outside);
  EXPECT_GT(rays, 12000);
  EXPECT_EQ(rehit, 0) << first_failure;
  EXPECT_EQ(wrong_exit, 0) << first_failure;
}

}  // namespace
}  // namespace prism
