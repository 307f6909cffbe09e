// Ray: origin, direction, the parametric interval [t_min, t_max] it may hit in, and the triangle it leaves.
#pragma once

#include <limits>

#include "core/vec3.h"

namespace prism {

// A triangle as Embree names it (instance, geometry, primitive); `none` for no triangle.
struct TriangleId {
  static constexpr unsigned kNone = ~0u;
  unsigned instance = kNone, geometry = kNone, primitive = kNone;
  bool valid() const { return geometry != kNone; }
};

struct Ray {
  Ray() = default;
  Ray(const Vec3& origin_, const Vec3& dir_, float t_min_ = 0.0f,
      float t_max_ = std::numeric_limits<float>::infinity(), TriangleId leaves_ = {})
      : origin(origin_), dir(dir_), t_min(t_min_), t_max(t_max_), leaves(leaves_) {}

  Vec3 origin;
  Vec3 dir;  // not necessarily unit length
  float t_min = 0.0f;
  float t_max = std::numeric_limits<float>::infinity();
  // The triangle this ray was spawned from: a plane is never met twice by one ray, so any hit
  // on it is Embree's rounding (docs/NUMERICS.md, "Own-face hits") and is ignored.
  TriangleId leaves;
  // A cone around the ray, for the footprint of texture lookups where it meets a surface (ray
  // cones, Akenine-Moller et al. 2019): its width at the origin, and how fast it widens per unit of
  // distance (radians). A camera ray's cone spans its pixel; 0, 0: a thin ray.
  float cone_width = 0;
  float cone_spread = 0;

  // The cone's width at parameter t.
  float cone_width_at(float t) const { return cone_spread > 0 ? cone_width + cone_spread * t * length(dir) : cone_width; }
};

}  // namespace prism
