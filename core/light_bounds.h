// LightBounds: where a group of lights sits, which way it shines and how much it emits, to judge
// from a shading point how much the group can matter (Conty Estevez & Kulla 2018, "Importance
// Sampling of Many Lights with Adaptive Tree Splitting", sec. 4).
#pragma once

#include "core/scene_desc.h"
#include "core/vec3.h"

namespace prism {

// The unit directions within angle theta of the unit axis w; cos_theta = -1 holds every direction.
struct DirectionCone {
  Vec3 w{0, 0, 1};
  float cos_theta = 1;

  static DirectionCone every_direction() { return {{0, 0, 1}, -1.0f}; }
};

// The smallest cone holding both (pbrt-v4 sec. 3.8.4 builds it the same way).
DirectionCone cone_union(const DirectionCone& a, const DirectionCone& b);

struct LightBounds {
  Bounds3 box;              // where the emitting points are
  DirectionCone normals;    // the emitting normals (theta_o); every direction for points and spheres
  float cos_emit = 0;       // cos theta_e: how far past a normal light leaves (pi/2 for a surface)
  double power = 0;         // luminance-weighted emitted power
  bool two_sided = false;   // emits along -normal too
};

// Bounds of both groups; `cones` unites their normals' cones (cone_union, or a looser one that is
// cheaper to find).
LightBounds merge(const LightBounds& a, const LightBounds& b,
                  DirectionCone (*cones)(const DirectionCone&, const DirectionCone&) = cone_union);

// The orientation measure M_Omega of Conty Estevez & Kulla (eq. 1): the solid angle the group's
// emission spreads over, cosine-weighted past theta_o; pi for a one-sided planar emitter.
float orientation_measure(const LightBounds& b);

}  // namespace prism
