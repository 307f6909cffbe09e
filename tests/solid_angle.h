// The solid angle of a triangle seen from the origin, in double: the tests' own reference.
#pragma once

#include <cmath>

#include "core/vec3.h"

namespace prism::test {

// Van Oosterom and Strackee (IEEE TBME 1983).
inline double triangle_solid_angle(Vec3 a, Vec3 b, Vec3 c) {
  const double la = length(a), lb = length(b), lc = length(c);
  const double num = std::abs(dot(a, cross(b, c)));
  const double den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  return 2.0 * std::atan2(num, den);
}

}  // namespace prism::test
