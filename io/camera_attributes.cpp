#include "io/camera_attributes.h"

#include <cmath>

#include "core/constants.h"

namespace prism {
namespace {

// Row-vector matrix product a * b.
ExrMatrix multiply(const ExrMatrix& a, const ExrMatrix& b) {
  ExrMatrix m{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < 4; ++k) m[size_t(4 * r + c)] += a[size_t(4 * r + k)] * b[size_t(4 * k + c)];
  return m;
}

}  // namespace

ExrMatrix world_to_camera_matrix(const Camera& camera) {
  // Rows of the rotation part hold the camera axes as columns: x_c = dot(p - o, right), y_c =
  // dot(p - o, up), z_c = dot(p - o, forward) with forward = the glTF camera's -Z.
  const Vec3 r = camera.right(), u = camera.up(), f = camera.forward(), o = camera.position();
  return {r.x, u.x, f.x, 0,  //
          r.y, u.y, f.y, 0,  //
          r.z, u.z, f.z, 0,  //
          -dot(o, r), -dot(o, u), -dot(o, f), 1};
}

ExrMatrix world_to_ndc_matrix(const Camera& camera) {
  const float hw = camera.half_width(), hh = camera.half_height();
  ExrMatrix projection;
  if (camera.desc().projection == Projection::Perspective) {
    // x_ndc = (1 + x_c / (z_c hw)) / 2 and y_ndc = (1 - y_c / (z_c hh)) / 2: w = z_c; z/w = 1.
    projection = {0.5f / hw, 0,          0, 0,  //
                  0,         -0.5f / hh, 0, 0,  //
                  0.5f,      0.5f,       1, 1,  //
                  0,         0,          0, 0};
  } else {
    // Orthographic: x_ndc = (1 + x_c / hw) / 2, y_ndc = (1 - y_c / hh) / 2, w = 1; z kept.
    projection = {0.5f / hw, 0,          0, 0,  //
                  0,         -0.5f / hh, 0, 0,  //
                  0,         0,          1, 0,  //
                  0.5f,      0.5f,       0, 1};
  }
  return multiply(world_to_camera_matrix(camera), projection);
}

std::vector<ExrAttribute> camera_attributes(const Camera& camera) {
  std::vector<ExrAttribute> a = {{"worldToCamera", world_to_camera_matrix(camera)},
                                 {"worldToNDC", world_to_ndc_matrix(camera)}};
  if (camera.desc().projection == Projection::Perspective) {
    const double degrees = 180.0 / kPi;
    a.push_back({"prism/projection", std::string("perspective")});
    a.push_back({"prism/fovVertical", 2.0 * std::atan(double(camera.half_height())) * degrees});
    a.push_back({"prism/fovHorizontal", 2.0 * std::atan(double(camera.half_width())) * degrees});
  } else {
    a.push_back({"prism/projection", std::string("orthographic")});
    a.push_back({"prism/orthoHalfWidth", double(camera.half_width())});
    a.push_back({"prism/orthoHalfHeight", double(camera.half_height())});
  }
  return a;
}

}  // namespace prism
