#include "core/environment_light.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/arctangent.h"
#include "core/constants.h"
#include "core/memory_limit.h"
#include "core/sampling.h"

namespace prism {

EnvironmentLight::EnvironmentLight(const SceneDesc& desc) {
  const EnvironmentDesc& env = desc.environment;
  present_ = env.present;
  if (!present_) return;
  scale_ = env.color;
  cos_rot_ = std::cos(env.rotation);
  sin_rot_ = std::sin(env.rotation);
  if (env.image >= 0 && env.image < static_cast<int>(desc.images.size())) {
    image_ = &desc.images[env.image];
    const int w = image_->width, h = image_->height;
    // The map is in memory already; its distribution comes on top (a float per texel).
    require_memory(image_->memory_bytes() + Distribution2D::footprint(w, h),
                   image_->name + ": the environment map with its sampling distribution");
    // Texels weighted by luminance and by the solid angle of their row (sin theta). Row by row:
    // an 8K map's grid of weights in doubles alone would take 256 MiB.
    const auto row_sin = [h](int y) { return std::sin(kPi * (y + 0.5) / h); };
    distribution_ = Distribution2D(w, h, [&](int y, std::vector<double>& row) {
      const double sin_t = row_sin(y);
      for (int x = 0; x < w; ++x)
        row[size_t(x)] = double(std::max(0.0f, luminance(image_->texel(x, y).rgb * scale_))) * sin_t;
    });
    // The mean over the sphere: the weights' total over the solid angle they stand for.
    double solid_angle_sum = 0;
    for (int y = 0; y < h; ++y) solid_angle_sum += row_sin(y);
    mean_luminance_ = solid_angle_sum > 0 ? distribution_.total() / (solid_angle_sum * w) : 0.0;
  } else {
    mean_luminance_ = std::max(0.0f, luminance(scale_));
  }
  if (!(mean_luminance_ > 0)) present_ = false;  // a black sky lights nothing
}

Vec2 EnvironmentLight::direction_to_uv(const Vec3& w) const {
  // Undo the rotation about +Y, then longitude from -Z toward +X, latitude from +Y.
  const float x = cos_rot_ * w.x - sin_rot_ * w.z;
  const float z = sin_rot_ * w.x + cos_rot_ * w.z;
  const float phi = atan2_fast(x, -z);  // 0 toward -Z
  // The polar angle as an arctangent of the height over the distance from the axis: as exact near
  // the poles as at the horizon (acos(w.y) loses bits there), and it needs no unit w.
  const float theta = atan2_fast(std::sqrt(w.x * w.x + w.z * w.z), w.y);
  return {0.5f + phi * kInvTwoPi, theta * kInvPi};
}

Vec3 EnvironmentLight::uv_to_direction(Vec2 uv) const {
  const float phi = (uv.x - 0.5f) * kTwoPi;  // in [-pi, pi]
  const SinCos polar = sin_cos_half_turn(uv.y * kPi), azimuth = sin_cos_half_turn(std::abs(phi));
  const float s = polar.sin;
  const float x = s * std::copysign(azimuth.sin, phi), z = -s * azimuth.cos;
  return {cos_rot_ * x + sin_rot_ * z, polar.cos, -sin_rot_ * x + cos_rot_ * z};
}

Rgb EnvironmentLight::radiance(const Vec3& w) const {
  if (!present_) return {};
  if (!image_) return scale_;
  return map_radiance(direction_to_uv(w));
}

EnvironmentLight::Seen EnvironmentLight::seen(const Vec3& w) const {
  if (!present_) return {};
  if (!image_) return {scale_, kInvFourPi};
  return seen_at(direction_to_uv(w));
}

Vec2 EnvironmentLight::prefetch(const Vec3& w) const {
  const Vec2 uv = direction_to_uv(w);
  const auto [x, y] = grid_cell(uv, image_->width, image_->height);
  image_->prefetch(x, y);
  distribution_.prefetch(uv);
  return uv;
}

void EnvironmentLight::sample(const Vec2* u, int n, Sample* out) const {
  if (!image_) {
    for (int i = 0; i < n; ++i) out[i] = {sample_uniform_sphere(u[i]), {scale_, kInvFourPi}};
    return;
  }
  constexpr int kBatch = 8;
  for (int first = 0; first < n; first += kBatch) {
    const int m = std::min(n - first, kBatch);
    Vec2 uv[kBatch];
    float pdf_uv[kBatch];
    distribution_.sample(u + first, m, uv, pdf_uv);
    // Radiance and density are looked up from the direction, as for any other direction: a sample
    // on a texel edge may round into the neighbour, and both must agree on which texel that is.
    // Every draw's texel is asked for before the first is read.
    Vec2 seen_uv[kBatch];
    for (int i = 0; i < m; ++i) {
      out[first + i].wi = uv_to_direction(uv[i]);
      seen_uv[i] = prefetch(out[first + i].wi);
    }
    for (int i = 0; i < m; ++i) {
      Seen& seen = out[first + i].seen;
      seen = seen_at(seen_uv[i]);
      if (!(pdf_uv[i] > 0)) seen.pdf = 0;
    }
  }
}

float EnvironmentLight::pdf(const Vec3& w) const {
  if (!present_) return 0;
  if (!image_) return kInvFourPi;
  return map_pdf(direction_to_uv(w));
}

// The nearest texel: the radiance is piecewise constant exactly as the sampling density is.
Rgb EnvironmentLight::map_radiance(Vec2 uv) const {
  const auto [x, y] = grid_cell(uv, image_->width, image_->height);
  return image_->texel(x, y).rgb * scale_;
}

float EnvironmentLight::map_pdf(Vec2 uv) const {
  const float sin_t = sin_cos_half_turn(uv.y * kPi).sin;
  return sin_t > 0 ? distribution_.pdf(uv) / (2.0f * kPi * kPi * sin_t) : 0.0f;
}

}  // namespace prism
