// Camera: turns a film position into a primary ray (glTF perspective and orthographic models).
#pragma once

#include <string>

#include "core/ray.h"
#include "core/scene_desc.h"

namespace prism {

class Camera {
 public:
  Camera(const CameraDesc& desc, int width, int height);

  // Ray through film position (fx, fy) in pixels: x to the right, y down, (0,0) the top-left corner.
  Ray generate_ray(float fx, float fy) const;

  const CameraDesc& desc() const { return desc_; }

  // Planar depth of p: its distance along the view axis (camera-space z), for the depth AOV.
  float planar_depth(const Vec3& p) const { return dot(p - position_, forward_); }
  // The orthonormal view frame (right, up, forward = the local -Z), its origin, and the half
  // extents of the image plane at unit distance (perspective) or in scene units (orthographic).
  const Vec3& position() const { return position_; }
  const Vec3& right() const { return right_; }
  const Vec3& up() const { return up_; }
  const Vec3& forward() const { return forward_; }
  float half_width() const { return half_w_; }
  float half_height() const { return half_h_; }

  // The same camera in coordinates whose origin sits at world position `origin` (a scene's render
  // origin, Scene::origin()); the shift composes in double, before anything is rounded to float.
  Camera relative_to(const Vec3& origin) const;

 private:
  CameraDesc desc_;
  int width_, height_;
  Vec3 position_, right_, up_, forward_;  // orthonormal, scale removed from the node transform
  float half_w_, half_h_;                 // tan(fov/2)-scaled (perspective) or magnifications (ortho)
};

// Picks a camera by name or index ("" = the first camera in node order). With no cameras in
// the scene, returns a perspective camera that frames its bounds. Throws std::invalid_argument
// naming the choices when `which` matches nothing.
CameraDesc select_camera(const SceneDesc& scene, const std::string& which);

// A perspective camera looking along -Z at the bounds, far enough to see all of them.
CameraDesc framing_camera(const Bounds3& bounds);

// The image size a camera suggests when the user gives none: 512 pixels high, the width from
// the camera's aspect ratio (square when it has none).
void default_resolution(const CameraDesc& camera, int& width, int& height);

}  // namespace prism
