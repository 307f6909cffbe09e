// Ray: origin, direction and the parametric interval [t_min, t_max] it may hit in.
#pragma once

#include <limits>

#include "core/vec3.h"

namespace prism {

struct Ray {
  Vec3 origin;
  Vec3 dir;  // not necessarily unit length
  float t_min = 0.0f;
  float t_max = std::numeric_limits<float>::infinity();
};

}  // namespace prism
