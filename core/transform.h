// Transform: an affine 3D transform with its inverse, for points, vectors and normals.
#pragma once

#include <array>

#include "core/vec3.h"

namespace prism {

class Transform {
 public:
  // Identity.
  Transform();
  // From a row-major 3x4 affine matrix (the bottom row is 0 0 0 1). A singular matrix keeps
  // its forward map and gets a zero inverse; is_invertible() reports it.
  explicit Transform(const std::array<double, 12>& row_major_3x4);
  // From a column-major 4x4 matrix, as glTF stores node matrices.
  static Transform from_column_major(const std::array<double, 16>& m);
  static Transform translate(const Vec3& t);
  static Transform scale(const Vec3& s);
  // Rotation by the unit quaternion (x, y, z, w).
  static Transform rotate_quaternion(double x, double y, double z, double w);
  static Transform look_at(const Vec3& eye, const Vec3& target, const Vec3& up);

  Transform operator*(const Transform& rhs) const;
  Transform inverse() const;

  Vec3 point(const Vec3& p) const;
  Vec3 vector(const Vec3& v) const;
  // Normals transform with the inverse transpose; the result is not normalised.
  Vec3 normal(const Vec3& n) const;

  bool is_invertible() const { return invertible_; }
  bool is_identity() const { return identity_; }
  // True when the linear part flips orientation (negative determinant): mirrored instances
  // must flip their winding-derived normals.
  bool flips_handedness() const { return determinant_ < 0; }
  double determinant() const { return determinant_; }
  const std::array<double, 12>& matrix() const { return m_; }
  // Row-major 3x4 in float, the layout Embree's RTC_FORMAT_FLOAT3X4_ROW_MAJOR expects.
  std::array<float, 12> matrix_float() const;

 private:
  std::array<double, 12> m_;
  std::array<double, 12> inv_;
  double determinant_ = 1.0;
  bool invertible_ = true;
  bool identity_ = true;
};

}  // namespace prism
