// Frame: an orthonormal basis around a unit normal, to move directions to and from local shading space.
#pragma once

#include <cmath>

#include "core/vec3.h"

namespace prism {

struct Frame {
  Vec3 s, t, n;

  // Branchless basis from a unit vector: Duff et al., "Building an Orthonormal Basis,
  // Revisited", JCGT 6(1), 2017.
  static Frame from_normal(const Vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
  }

  Vec3 to_local(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3 to_world(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace prism
