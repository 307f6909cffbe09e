#include "core/camera.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

namespace prism {

Camera::Camera(const CameraDesc& desc, int width, int height) : desc_(desc), width_(width), height_(height) {
  const Transform& m = desc.camera_to_world;
  position_ = m.point(Vec3(0, 0, 0));
  right_ = normalize(m.vector(Vec3(1, 0, 0)));
  // Gram-Schmidt so a sheared or scaled node still gives an orthonormal view frame.
  Vec3 up = m.vector(Vec3(0, 1, 0));
  up = normalize(up - right_ * dot(up, right_));
  up_ = up;
  forward_ = cross(up_, right_);  // -Z of a right-handed frame
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  if (desc.projection == Projection::Perspective) {
    half_h_ = std::tan(0.5f * desc.yfov);
  } else {
    half_h_ = desc.ymag;
  }
  half_w_ = half_h_ * aspect;
}

Camera Camera::relative_to(const Vec3& origin) const {
  CameraDesc moved = desc_;
  moved.camera_to_world = Transform::translate(-origin) * desc_.camera_to_world;
  return Camera(moved, width_, height_);
}

Ray Camera::generate_ray(float fx, float fy) const {
  const float sx = (2.0f * fx / static_cast<float>(width_) - 1.0f) * half_w_;
  const float sy = (1.0f - 2.0f * fy / static_cast<float>(height_)) * half_h_;
  Ray ray;
  if (desc_.projection == Projection::Perspective) {
    ray.origin = position_;
    const Vec3 d = forward_ + right_ * sx + up_ * sy;
    const float len = length(d);
    ray.dir = d / len;
    // A pixel is 2 half_h / height wide at unit distance along the axis, len away along the ray.
    ray.cone_spread = 2.0f * half_h_ / (static_cast<float>(height_) * len);
    // Clip planes are perpendicular to the view axis: convert plane depth to ray distance.
    ray.t_min = desc_.znear * len;
    if (desc_.zfar > 0) ray.t_max = desc_.zfar * len;
  } else {
    ray.origin = position_ + right_ * sx + up_ * sy;
    ray.dir = forward_;
    ray.cone_width = 2.0f * half_h_ / static_cast<float>(height_);  // a pixel's width, the same all along
    ray.t_min = desc_.znear;
    if (desc_.zfar > 0) ray.t_max = desc_.zfar;
  }
  return ray;
}

CameraDesc select_camera(const SceneDesc& scene, const std::string& which) {
  if (scene.cameras.empty()) {
    if (!which.empty())
      throw std::invalid_argument("camera '" + which + "' requested, but the scene has no cameras");
    return framing_camera(scene_bounds(scene));
  }
  if (which.empty()) return scene.cameras.front();
  for (const auto& c : scene.cameras)
    if (c.name == which || c.node_name == which) return c;
  if (std::all_of(which.begin(), which.end(), [](unsigned char ch) { return std::isdigit(ch); }) &&
      which.size() < 9) {
    const size_t index = std::stoul(which);
    if (index < scene.cameras.size()) return scene.cameras[index];
  }
  std::string names;
  for (size_t i = 0; i < scene.cameras.size(); ++i) {
    if (i) names += ", ";
    names += std::to_string(i) + " '" + scene.cameras[i].name + "'";
  }
  throw std::invalid_argument("no camera named or numbered '" + which + "'; the scene has: " + names);
}

CameraDesc framing_camera(const Bounds3& bounds) {
  CameraDesc cam;
  cam.name = "(framing camera)";
  cam.projection = Projection::Perspective;
  cam.yfov = 0.6981317f;  // 40 degrees
  Vec3 center{0, 0, 0};
  float radius = 1.0f;
  if (!bounds.empty()) {
    center = bounds.center();
    radius = std::max(0.5f * length(bounds.diagonal()), 1e-6f);
  }
  // Distance at which the bounding sphere fits the vertical field of view, looking from +Z
  // slightly above, as a modelling package's front view does.
  const float distance = radius / std::sin(0.5f * cam.yfov) * 1.05f;
  const Vec3 eye = center + normalize(Vec3(0, 0.25f, 1)) * distance;
  cam.camera_to_world = Transform::look_at(eye, center, Vec3(0, 1, 0));
  return cam;
}

void default_resolution(const CameraDesc& camera, int& width, int& height) {
  height = 512;
  float aspect = 1.0f;
  if (camera.projection == Projection::Perspective && camera.aspect_ratio) aspect = *camera.aspect_ratio;
  if (camera.projection == Projection::Orthographic && camera.ymag > 0) aspect = camera.xmag / camera.ymag;
  if (!(aspect > 0.01f && aspect < 100.0f)) aspect = 1.0f;
  width = std::max(1, static_cast<int>(std::lround(512.0f * aspect)));
}

}  // namespace prism
