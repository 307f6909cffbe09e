// Scene: the Embree acceleration structure over a SceneDesc, with hit reconstruction and emitters.
#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <vector>

#include "core/emitters.h"
#include "core/ray.h"
#include "core/scene_desc.h"
#include "core/surface_hit.h"

namespace prism {

class Scene {
 public:
  // Validates `desc` (indices in range; throws std::invalid_argument naming the element) and
  // builds the BVH: one Embree scene per mesh, instanced once per placement; all spheres in
  // one user geometry.
  explicit Scene(SceneDesc desc);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  // Nearest hit in (t_min, t_max). `coherent` marks camera rays for Embree's packet heuristics.
  bool intersect(const Ray& ray, SurfaceHit& hit, bool coherent = false) const;
  // True when anything blocks the ray within (t_min, t_max).
  bool occluded(const Ray& ray) const;

  const SceneDesc& desc() const { return desc_; }
  const Emitters& emitters() const { return emitters_; }
  const SceneFeatures& features() const { return features_; }
  double build_seconds() const { return build_seconds_; }

 private:
  void reconstruct_triangle_hit(const RTCRayHit& rh, SurfaceHit& hit) const;
  void reconstruct_sphere_hit(const Ray& ray, const RTCRayHit& rh, SurfaceHit& hit) const;

  SceneDesc desc_;
  SceneFeatures features_;
  RTCScene top_ = nullptr;
  std::vector<RTCScene> mesh_scenes_;
  unsigned sphere_geom_id_ = RTC_INVALID_GEOMETRY_ID;
  Emitters emitters_;
  double build_seconds_ = 0;
};

// Throws std::invalid_argument if any index in `desc` is out of range.
void validate_scene_desc(const SceneDesc& desc);

}  // namespace prism
