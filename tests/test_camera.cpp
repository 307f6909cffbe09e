// Cameras: glTF perspective and orthographic projection, clip planes, and the framing camera.
#include <gtest/gtest.h>

#include <cmath>

#include "core/camera.h"

namespace prism {
namespace {

TEST(Camera, PerspectiveLooksDownMinusZWithItsFieldOfView) {
  CameraDesc d;
  d.yfov = 1.0f;
  d.znear = 0.5f;
  const Camera cam(d, 200, 100);
  const Ray centre = cam.generate_ray(100, 50);
  EXPECT_NEAR(centre.dir.z, -1.0f, 1e-6f);
  EXPECT_NEAR(centre.t_min, 0.5f, 1e-6f);
  const Ray top = cam.generate_ray(100, 0);  // top edge: half the vertical field of view, upward
  EXPECT_NEAR(std::atan2(top.dir.y, -top.dir.z), 0.5f, 1e-5f);
  const Ray right = cam.generate_ray(200, 50);  // the image is twice as wide as high
  EXPECT_NEAR(right.dir.x / -right.dir.z, 2.0f * std::tan(0.5f), 1e-5f);
  EXPECT_NEAR(length(right.dir), 1.0f, 1e-6f);
}

TEST(Camera, NodeScaleDoesNotDistortTheView) {
  CameraDesc d;
  d.yfov = 1.0f;
  d.camera_to_world = Transform::translate(Vec3(1, 2, 3)) * Transform::scale(Vec3(5, 5, 5));
  const Camera cam(d, 100, 100);
  const Ray top = cam.generate_ray(50, 0);
  EXPECT_NEAR(std::atan2(top.dir.y, -top.dir.z), 0.5f, 1e-5f);
  EXPECT_NEAR(top.origin.x, 1.0f, 1e-6f);
}

TEST(Camera, OrthographicRaysAreParallel) {
  CameraDesc d;
  d.projection = Projection::Orthographic;
  d.xmag = 4;
  d.ymag = 2;
  d.camera_to_world = Transform::translate(Vec3(0, 0, 10));
  const Camera cam(d, 200, 100);
  const Ray a = cam.generate_ray(0, 0), b = cam.generate_ray(200, 100);
  EXPECT_EQ(a.dir, b.dir);
  EXPECT_NEAR(a.origin.x, -4.0f, 1e-5f);
  EXPECT_NEAR(a.origin.y, 2.0f, 1e-5f);
  EXPECT_NEAR(b.origin.x, 4.0f, 1e-5f);
  EXPECT_NEAR(a.origin.z, 10.0f, 1e-6f);
}

TEST(Camera, FramingCameraSeesTheWholeBounds) {
  Bounds3 b;
  b.extend(Vec3(-3, 0, 2));
  b.extend(Vec3(5, 1, 4));
  const CameraDesc d = framing_camera(b);
  const Camera cam(d, 100, 100);
  const Ray centre = cam.generate_ray(50, 50);
  // The view axis passes through the centre of the bounds.
  const Vec3 to_centre = normalize(b.center() - centre.origin);
  EXPECT_NEAR(dot(to_centre, centre.dir), 1.0f, 1e-5f);
  // Every corner is inside the field of view.
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z);
    const float cos_angle = dot(normalize(corner - centre.origin), centre.dir);
    EXPECT_GT(cos_angle, std::cos(0.5f * d.yfov));
  }
}

}  // namespace
}  // namespace prism
