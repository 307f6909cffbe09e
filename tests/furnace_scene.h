// A furnace for tests: a closed, uniformly emitting diffuse box whose radiance is known exactly.
#pragma once

#include <cmath>

#include "core/camera.h"
#include "core/scene_desc.h"
#include "scene_builders.h"

namespace prism::test {

// Every bounce k adds a^k Le, up to max depth d: Le (1 - a^(d+1)) / (1 - a).
inline double furnace_radiance(double le, double albedo, int max_depth) {
  return le * (1.0 - std::pow(albedo, max_depth + 1)) / (1.0 - albedo);
}

inline SceneDesc furnace_box(double le, double albedo, float scale = 1.0f) {
  SceneDesc desc;
  const int m = add_material(desc, Rgb(float(albedo)), Rgb(float(le)));
  add_inward_box(desc, Vec3(-1.0f, -0.7f, -1.3f) * scale, Vec3(1.2f, 0.9f, 1.0f) * scale, m);
  return desc;
}

// A wide-angle camera inside the furnace, looking at a corner.
inline CameraDesc furnace_camera(const Vec3& eye = Vec3(0.1f)) {
  CameraDesc cam;
  cam.camera_to_world = Transform::look_at(eye, eye + Vec3(0.3f, 0.2f, -1.0f), Vec3(0, 1, 0));
  cam.yfov = 1.6f;
  return cam;
}

}  // namespace prism::test
