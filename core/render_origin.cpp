#include "core/render_origin.h"

#include <algorithm>
#include <cmath>

namespace prism {

Vec3 choose_render_origin(const SceneDesc& scene) {
  const Bounds3 bounds = scene_bounds(scene);
  if (bounds.empty()) return Vec3(0.0f);
  const Vec3 centre = bounds.center();
  const Vec3 size = bounds.diagonal();
  const float far = std::max({std::abs(centre.x), std::abs(centre.y), std::abs(centre.z)});
  const float extent = std::max({size.x, size.y, size.z});
  if (!std::isfinite(far) || !(far > extent)) return Vec3(0.0f);
  return centre;
}

void move_origin(SceneDesc& scene, const Vec3& origin) {
  if (origin == Vec3(0.0f)) return;
  const Transform shift = Transform::translate(-origin);
  for (InstanceDesc& inst : scene.instances) inst.object_to_world = shift * inst.object_to_world;
  for (SphereDesc& s : scene.spheres) s.center = shift.point(s.center);
  for (PunctualLightDesc& l : scene.lights) l.position = shift.point(l.position);
  for (CameraDesc& c : scene.cameras) c.camera_to_world = shift * c.camera_to_world;
}

}  // namespace prism
