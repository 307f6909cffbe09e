// CausticCasters: the smooth metal and glass objects of a scene, as bounding spheres a path can aim
// its bounce directions at, so that light reaching a diffuse surface through them is found.
#pragma once

#include <vector>

#include "core/scene_desc.h"

namespace prism {

// The casters seen from one shading point: a cone of directions for each caster that is worth
// aiming at from there. Directions are drawn by choosing one of the cones uniformly, then a
// direction uniformly inside it; pdf() is the density of that draw over all the cones.
class CasterView {
 public:
  static constexpr int kMaxCones = 16;  // the first this many that qualify (largest first)

  // Empty. User-provided, so that a view made at every vertex does not zero its arrays first.
  CasterView() {}

  bool empty() const { return count_ == 0; }
  int size() const { return count_; }
  // u_pick chooses the cone, u_dir the direction in it; the result is a unit vector.
  Vec3 sample(float u_pick, Vec2 u_dir) const;
  // Solid-angle density of sample() drawing unit direction w.
  float pdf(const Vec3& w) const;

 private:
  friend class CausticCasters;
  // Cone k: its unit axis (toward the caster's centre), its half-angle as a cosine, 1 - that
  // cosine without cancellation, and its density 1 / solid angle. Left uninitialised beyond count_:
  // a view is made at every vertex of a scene with casters.
  float axis_x_[kMaxCones], axis_y_[kMaxCones], axis_z_[kMaxCones];
  float cos_max_[kMaxCones], one_minus_cos_max_[kMaxCones], density_[kMaxCones];
  int count_ = 0;
};

class CausticCasters {
 public:
  // A caster is a mesh primitive or analytic sphere whose material has a smooth (roughness factor
  // at most kMaxRoughness) metal or transmission lobe: the surfaces that focus light into caustics
  // next-event estimation cannot reach (its shadow rays stop at them). Positions are world space
  // (the instance transforms applied); each caster is bounded by a sphere around its box.
  static constexpr float kMaxRoughness = 0.2f;
  static constexpr int kMaxCasters = 64;  // the largest, by bounding radius, when there are more

  CausticCasters() = default;
  explicit CausticCasters(const SceneDesc& desc);

  bool empty() const { return casters_.empty(); }
  size_t size() const { return casters_.size(); }
  // The casters worth aiming at from point p on a surface with unit normal n (the side light is
  // reflected to): those whose bounding sphere subtends a cone of half-angle under 45 degrees (a
  // wider cone is found often enough by the BSDF's own samples, and p is outside the sphere) and
  // that rise above the surface's tangent plane.
  void view(const Vec3& p, const Vec3& n, CasterView& out) const;

  static bool is_caster(const MaterialDesc& m);

 private:
  struct Sphere {
    Vec3 center;
    float radius;
  };
  std::vector<Sphere> casters_;
};

}  // namespace prism
