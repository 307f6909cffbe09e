// Cameras at the extremes: fields of view from 0.1 to 179 degrees, orthographic, a camera inside
// an object, a near plane of 0: rays stay finite and distinct, and a furnace reads its radiance.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/camera.h"
#include "core/constants.h"
#include "furnace_scene.h"
#include "scene_builders.h"

namespace prism {
namespace {

constexpr int kNoRoulette = 1 << 20;
constexpr float kDegree = kPi / 180.0f;

CameraDesc camera_at(const Vec3& eye, const Vec3& target, Projection projection = Projection::Perspective) {
  CameraDesc cam;
  cam.projection = projection;
  cam.camera_to_world = Transform::look_at(eye, target, Vec3(0, 1, 0));
  return cam;
}

// Every pixel of a 64x64 image gets a finite, unit direction, and directions turn monotonically
// across a row and down a column: at 0.1 degrees a pixel spans 2.7e-5 rad, at 179 degrees the
// corner rays point almost sideways.
TEST(CameraExtremes, FieldOfViewFromATenthOfADegreeTo179GivesDistinctFiniteRays) {
  for (float degrees : {0.1f, 1.0f, 60.0f, 120.0f, 179.0f}) {
    CameraDesc desc = camera_at(Vec3(0.0f), Vec3(0, 0, -1));
    desc.yfov = degrees * kDegree;
    const int n = 64;
    const Camera camera(desc, n, n);
    for (int y = 0; y < n; ++y) {
      float previous_x = -2;
      for (int x = 0; x < n; ++x) {
        const Ray r = camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f);
        ASSERT_TRUE(std::isfinite(r.dir.x) && std::isfinite(r.dir.y) && std::isfinite(r.dir.z)) << degrees;
        ASSERT_NEAR(length(r.dir), 1.0f, 1e-6f) << degrees;
        ASSERT_LT(r.dir.z, 0.0f) << degrees;  // in front of the camera
        ASSERT_GT(r.dir.x, previous_x) << degrees << " degrees, pixel " << x << "," << y;
        previous_x = r.dir.x;
      }
    }
    // The vertical extent is the field of view: the edge rays are yfov/2 off the axis.
    const Ray top = camera.generate_ray(0.5f * n, 0.0f);
    EXPECT_NEAR(std::atan2(top.dir.y, -top.dir.z), 0.5f * desc.yfov, 1e-5f * std::max(1.0f, desc.yfov)) << degrees;
  }
}

// Orthographic rays are parallel and their origins are spaced 2 xmag / width apart.
TEST(CameraExtremes, OrthographicRaysAreParallel) {
  CameraDesc desc = camera_at(Vec3(1, 2, 3), Vec3(1, 2, 0), Projection::Orthographic);
  desc.xmag = desc.ymag = 1e-3f;
  const Camera camera(desc, 32, 32);
  const Ray a = camera.generate_ray(0.5f, 0.5f), b = camera.generate_ray(1.5f, 0.5f);
  EXPECT_EQ(a.dir, b.dir);
  EXPECT_NEAR(b.origin.x - a.origin.x, 2e-3f / 32, 2.5e-7f);  // two float spacings at x = 1..2
}

// A furnace (closed emitting box) looks the same in every direction, so any camera inside it
// must read the closed-form radiance: at 0.1 and 179 degrees, orthographic, and with a near
// plane of 0 from a point on a wall.
TEST(CameraExtremes, FurnaceReadsItsRadianceThroughEveryCamera) {
  const double le = 1.0, albedo = 0.5;
  const int depth = 4;
  const double expected = test::furnace_radiance(le, albedo, depth);
  std::vector<std::pair<std::string, CameraDesc>> cameras;
  for (float degrees : {0.1f, 179.0f}) {
    CameraDesc c = camera_at(Vec3(0.1f), Vec3(0.4f, 0.3f, -0.9f));
    c.yfov = degrees * kDegree;
    cameras.push_back({std::to_string(degrees) + " degrees", c});
  }
  CameraDesc ortho = camera_at(Vec3(0.1f), Vec3(0.4f, 0.3f, -0.9f), Projection::Orthographic);
  ortho.xmag = ortho.ymag = 0.5f;
  cameras.push_back({"orthographic", ortho});
  // On the wall z = 1.0 (furnace_box spans z -1.3..1.0), looking in, near plane 0: the camera rays
  // start on the wall itself.
  CameraDesc on_wall = camera_at(Vec3(0.1f, 0.1f, 1.0f), Vec3(0.1f, 0.1f, 0.0f));
  on_wall.znear = 0.0f;
  cameras.push_back({"on a wall, near plane 0", on_wall});
  for (const auto& [name, cam] : cameras) {
    SCOPED_TRACE(name);
    test::expect_furnace(test::furnace_box(le, albedo), cam, albedo, depth, kNoRoulette, expected);
  }
}

// A camera inside an object: inside a solid glass sphere in the furnace. The camera is immersed
// in the glass (its rays meet the sphere from behind), and radiance inside a medium of index n is
// n^2 times the radiance outside (radiance over n^2 is invariant along a ray, Veach 1997 §5.2), so
// it must read n^2 Le / (1 - a): 2 at index 1 (the glass is invisible), 4.5 at index 1.5. Deep
// paths, so the crossings' share of the bounce budget does not matter.
TEST(CameraExtremes, CameraInsideAGlassObjectSeesTheFurnaceThroughIt) {
  const double le = 1.0, albedo = 0.5;
  const int depth = 64;
  for (float ior : {1.0f, 1.5f}) {
    SCOPED_TRACE("ior " + std::to_string(ior));
    SceneDesc desc = test::furnace_box(le, albedo);
    const int glass = test::add_glass(desc, ior);
    test::add_sphere(desc, Vec3(0.1f, 0.1f, 0.0f), 0.3f, glass);
    const CameraDesc cam = camera_at(Vec3(0.1f, 0.1f, 0.0f), Vec3(0.4f, 0.3f, -0.9f));
    test::expect_furnace(std::move(desc), cam, albedo, depth, kNoRoulette, double(ior) * ior * le / (1.0 - albedo));
  }
}

}  // namespace
}  // namespace prism
