// The unit normal and area of a triangle spanned by float corners, computed in double.
#pragma once

#include <cmath>

#include "core/vec3.h"

namespace prism {

struct FaceNormal {
  Vec3 normal;     // unit, along cross(p1 - p0, p2 - p0); zero when the corners are collinear
  float area = 0;  // zero when collinear (or below the smallest float)
};

// In double the edges of float corners are exact, and so are their products (24-bit mantissas
// multiply into 48 bits), so each component of the cross product is rounded once. A sliver whose
// float cross product would cancel into noise (its normal off by 0.95 in the worst of 4000 hits
// measured, tests/extremes/test_geometry_extremes.cpp) gets the plane its corners really span.
inline FaceNormal face_normal(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const double ax = double(p1.x) - p0.x, ay = double(p1.y) - p0.y, az = double(p1.z) - p0.z;
  const double bx = double(p2.x) - p0.x, by = double(p2.y) - p0.y, bz = double(p2.z) - p0.z;
  const double nx = ay * bz - az * by, ny = az * bx - ax * bz, nz = ax * by - ay * bx;
  const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
  FaceNormal f;
  if (!(len > 0) || !std::isfinite(len) || !(float(0.5 * len) > 0)) return f;
  f.normal = Vec3(float(nx / len), float(ny / len), float(nz / len));
  f.area = float(0.5 * len);
  return f;
}

}  // namespace prism
