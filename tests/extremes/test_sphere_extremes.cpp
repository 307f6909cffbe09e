// Spheres at the extremes: radius 1e-5 to 1e6, seen from inside, from just outside and from 1e5
// radii away, by rays spread over the disc and crowded at the silhouette: hit distance, point and
// normal against the exact values of the same float inputs, computed in long double.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/frame.h"
#include "core/pcg32.h"
#include "core/sampling.h"
#include "core/scene.h"
#include "core/surface_hit.h"
#include "scene_builders.h"

namespace prism {
namespace {

using Real = long double;

struct ExactRoots {
  Real disc;   // r^2 - |f|^2, f the offset of the closest approach (Hearn and Baker)
  Real t_near; // the nearest root ahead of the origin, or -1
};

ExactRoots exact_roots(const Vec3& c, float r, const Ray& ray) {
  Real o[3] = {Real(ray.origin.x) - c.x, Real(ray.origin.y) - c.y, Real(ray.origin.z) - c.z};
  Real d[3] = {ray.dir.x, ray.dir.y, ray.dir.z};
  const Real dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const Real b = -(o[0] * d[0] + o[1] * d[1] + o[2] * d[2]) / dd;  // t of the closest approach
  Real f2 = 0;
  for (int i = 0; i < 3; ++i) f2 += (o[i] + b * d[i]) * (o[i] + b * d[i]);
  ExactRoots out{Real(r) * r - f2, -1};
  if (out.disc < 0) return out;
  const Real h = std::sqrt(out.disc / dd);
  out.t_near = b - h > 0 ? b - h : (b + h > 0 ? b + h : -1);
  return out;
}

// Stated bounds: t within 4 float ulps of the exact root, plus 1e-6 r where the root is
// ill-conditioned at the silhouette; the point within its own error bound (what ray offsets rely
// on); the normal within 4e-6 rad (float normals are unit to about 1e-7).
TEST(SphereExtremes, HitDistancePointAndNormalAreExactToAStatedBoundAtEveryScale) {
  Pcg32 rng(5, 6);
  long hits = 0, grazing_hits = 0;
  for (float r : {1e-5f, 1e-3f, 1.0f, 1e3f, 1e6f}) {
    for (float distance : {0.5f, 1.001f, 3.0f, 1e3f, 1e5f}) {  // camera distance over the radius
      SceneDesc desc;
      const int m = test::add_material(desc, Rgb(0.5f));
      test::add_sphere(desc, Vec3(0.25f, -0.5f, 0.75f) * r, r, m);
      const Scene scene(std::move(desc));
      const SphereDesc& s = scene.desc().spheres[0];  // in the scene's own coordinates
      for (int i = 0; i < 400; ++i) {
        const Vec3 eye = s.center + sample_uniform_sphere({rng.next_float(), rng.next_float()}) * (distance * r);
        // Impact parameter over the radius: uniform over the disc, or crowded at the silhouette.
        const float u = i % 2 ? rng.next_float() : 1.0f - std::pow(10.0f, -2.0f - 5.0f * rng.next_float());
        const Frame frame = Frame::from_normal(normalize(s.center - eye));
        const float phi = kTwoPi * rng.next_float();
        const Vec3 aim = s.center + (frame.s * std::cos(phi) + frame.t * std::sin(phi)) * (u * r);
        const Ray ray{eye, normalize(aim - eye)};
        const ExactRoots exact = exact_roots(s.center, s.radius, ray);
        SurfaceHit hit;
        const bool found = scene.intersect(ray, hit);
        const std::string where = "r " + std::to_string(r) + " distance " + std::to_string(distance) + " u " + std::to_string(u);
        // Inside a band of 1e-9 r^2 around the silhouette either answer is right.
        if (std::abs(exact.disc) < 1e-9L * r * r) continue;
        ASSERT_EQ(found, exact.t_near > 0) << where;
        if (!found) continue;
        ++hits;
        grazing_hits += u > 0.999f;
        const Real t = exact.t_near;
        EXPECT_NEAR(hit.t, double(t), double(t) * 0x1p-21 + 1e-6 * r) << where;
        Real n[3], p_err = 0;
        for (int k = 0; k < 3; ++k) {
          const Real pk = Real(ray.origin[k]) + Real(ray.dir[k]) * t;
          n[k] = (pk - s.center[k]) / r;
          p_err = std::max(p_err, std::abs(Real(hit.p[k]) - pk) - Real(hit.p_error[k]));
        }
        EXPECT_LE(double(p_err), 0.0) << where << ": the point is outside its own error bound";
        Real n_err2 = 0;  // |n_exact - ng|: the angle between them, for small angles
        for (int k = 0; k < 3; ++k) n_err2 += (n[k] - hit.ng[k]) * (n[k] - hit.ng[k]);
        EXPECT_LT(double(std::sqrt(n_err2)), 4e-6) << where << " t " << hit.t << " exact " << double(t) << " disc " << double(exact.disc / (Real(r) * r));
      }
    }
  }
  EXPECT_GT(hits, 5000);
  EXPECT_GT(grazing_hits, 1000);  // the silhouette was really tested
}

}  // namespace
}  // namespace prism
