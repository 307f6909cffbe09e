// A small scene whose AOVs are known: a floor, a light above it and a ball, seen from above.
#pragma once

#include "core/camera.h"
#include "core/scene_desc.h"
#include "core/transform.h"
#include "scene_builders.h"

namespace prism::test {

inline const Rgb kAlbedo(0.6f, 0.4f, 0.2f);
inline const Rgb kLight(4.0f, 3.0f, 2.0f);
inline const Vec3 kLightCorner(-3, 1.2f, 2), kLightEdgeU(0, 4, 0), kLightEdgeV(6, 0, 0);
inline const Vec3 kBallCenter(-0.8f, -0.8f, 0.5f);
inline constexpr float kBallRadius = 0.5f;

// Object 0: a floor at z = 0 facing +z (material 0). Object 1: a light facing it from z = 2,
// seen at the image's top edge (material 1). Object 2: a sphere (the default material).
inline SceneDesc aov_scene() {
  SceneDesc desc;
  const int floor = add_material(desc, kAlbedo);
  const int light = add_material(desc, Rgb(0.0f), kLight);
  add_quad(desc, Vec3(-3, -3, 0), Vec3(6, 0, 0), Vec3(0, 6, 0), floor);
  desc.instances.back().name = "floor";
  add_quad(desc, kLightCorner, kLightEdgeU, kLightEdgeV, light);
  desc.instances.back().name = "light";
  add_sphere(desc, kBallCenter, kBallRadius, -1);
  desc.spheres.back().name = "ball";
  return desc;
}

// Looking straight down -z from z = 5.
inline CameraDesc top_camera() {
  CameraDesc cam;
  cam.camera_to_world = Transform::translate(Vec3(0, 0, 5));
  cam.yfov = 0.9f;
  return cam;
}

}  // namespace prism::test
