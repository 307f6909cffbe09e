#include "core/transform.h"

#include <cmath>

namespace prism {
namespace {

using Mat = std::array<double, 12>;

constexpr Mat kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};

double det3(const Mat& m) {
  return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
         m[2] * (m[4] * m[9] - m[5] * m[8]);
}

// Inverse of an affine map: invert the 3x3 part by cofactors, then the translation.
bool invert(const Mat& m, double det, Mat& out) {
  if (det == 0 || !std::isfinite(det)) {
    out.fill(0.0);
    return false;
  }
  const double id = 1.0 / det;
  out[0] = (m[5] * m[10] - m[6] * m[9]) * id;
  out[1] = (m[2] * m[9] - m[1] * m[10]) * id;
  out[2] = (m[1] * m[6] - m[2] * m[5]) * id;
  out[4] = (m[6] * m[8] - m[4] * m[10]) * id;
  out[5] = (m[0] * m[10] - m[2] * m[8]) * id;
  out[6] = (m[2] * m[4] - m[0] * m[6]) * id;
  out[8] = (m[4] * m[9] - m[5] * m[8]) * id;
  out[9] = (m[1] * m[8] - m[0] * m[9]) * id;
  out[10] = (m[0] * m[5] - m[1] * m[4]) * id;
  for (int r = 0; r < 3; ++r)
    out[r * 4 + 3] = -(out[r * 4] * m[3] + out[r * 4 + 1] * m[7] + out[r * 4 + 2] * m[11]);
  return true;
}

}  // namespace

Transform::Transform() : m_(kIdentity), inv_(kIdentity) {}

Transform::Transform(const std::array<double, 12>& row_major_3x4) : m_(row_major_3x4) {
  identity_ = m_ == kIdentity;
  determinant_ = det3(m_);
  invertible_ = invert(m_, determinant_, inv_);
}

Transform Transform::from_column_major(const std::array<double, 16>& c) {
  return Transform(Mat{c[0], c[4], c[8], c[12], c[1], c[5], c[9], c[13], c[2], c[6], c[10], c[14]});
}

Transform Transform::translate(const Vec3& t) { return Transform(Mat{1, 0, 0, t.x, 0, 1, 0, t.y, 0, 0, 1, t.z}); }

Transform Transform::scale(const Vec3& s) { return Transform(Mat{s.x, 0, 0, 0, 0, s.y, 0, 0, 0, 0, s.z, 0}); }

Transform Transform::rotate_quaternion(double x, double y, double z, double w) {
  const double n = std::sqrt(x * x + y * y + z * z + w * w);
  if (n > 0) {
    x /= n; y /= n; z /= n; w /= n;
  }
  return Transform(Mat{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), 0,
                       2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), 0,
                       2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), 0});
}

Transform Transform::look_at(const Vec3& eye, const Vec3& target, const Vec3& up) {
  // Camera-to-world for a camera at `eye` looking down its -Z axis at `target`.
  const Vec3 back = normalize(eye - target);
  Vec3 right = cross(up, back);
  if (length_squared(right) == 0) right = cross(Vec3(1, 0, 0), back);
  right = normalize(right);
  const Vec3 true_up = cross(back, right);
  return Transform(Mat{right.x, true_up.x, back.x, eye.x, right.y, true_up.y, back.y, eye.y,
                       right.z, true_up.z, back.z, eye.z});
}

Transform Transform::operator*(const Transform& rhs) const {
  const Mat& a = m_;
  const Mat& b = rhs.m_;
  Mat r{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) {
      double v = a[i * 4 + 0] * b[0 * 4 + j] + a[i * 4 + 1] * b[1 * 4 + j] + a[i * 4 + 2] * b[2 * 4 + j];
      if (j == 3) v += a[i * 4 + 3];
      r[i * 4 + j] = v;
    }
  }
  return Transform(r);
}

Transform Transform::inverse() const { return Transform(inv_); }

Vec3 Transform::point(const Vec3& p) const {
  const auto& m = m_;
  return {static_cast<float>(m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3]),
          static_cast<float>(m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7]),
          static_cast<float>(m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11])};
}

Vec3 Transform::vector(const Vec3& v) const {
  const auto& m = m_;
  return {static_cast<float>(m[0] * v.x + m[1] * v.y + m[2] * v.z),
          static_cast<float>(m[4] * v.x + m[5] * v.y + m[6] * v.z),
          static_cast<float>(m[8] * v.x + m[9] * v.y + m[10] * v.z)};
}

Vec3 Transform::normal(const Vec3& n) const {
  const auto& i = inv_;  // (M^-1)^T n
  return {static_cast<float>(i[0] * n.x + i[4] * n.y + i[8] * n.z),
          static_cast<float>(i[1] * n.x + i[5] * n.y + i[9] * n.z),
          static_cast<float>(i[2] * n.x + i[6] * n.y + i[10] * n.z)};
}

std::array<float, 12> Transform::matrix_float() const {
  std::array<float, 12> f{};
  for (int i = 0; i < 12; ++i) f[i] = static_cast<float>(m_[i]);
  return f;
}

}  // namespace prism
