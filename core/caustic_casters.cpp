#include "core/caustic_casters.h"

#include <algorithm>
#include <cmath>

#include "core/constants.h"
#include "core/frame.h"
#include "core/sampling.h"

namespace prism {
namespace {

// A cone wider than 45 degrees (sin^2 of its half-angle above 1/2) holds more than 15% of a
// cosine-weighted hemisphere's samples already: aiming at it buys little.
constexpr float kMaxSin2 = 0.5f;

}  // namespace

bool CausticCasters::is_caster(const MaterialDesc& m) {
  return ((m.metallic > 0 || m.is_transmissive()) && m.roughness <= kMaxRoughness);
}

CausticCasters::CausticCasters(const SceneDesc& desc) {
  for (const InstanceDesc& inst : desc.instances) {
    for (const PrimitiveDesc& prim : desc.meshes[size_t(inst.mesh)].primitives) {
      if (prim.triangle_count() == 0 || !is_caster(desc.material(prim.material))) continue;
      Bounds3 box;
      for (uint32_t i : prim.indices) box.extend(inst.object_to_world.point(prim.positions[i]));
      casters_.push_back({(box.lo + box.hi) * 0.5f, 0.5f * length(box.diagonal())});
    }
  }
  for (const SphereDesc& s : desc.spheres)
    if (is_caster(desc.material(s.material))) casters_.push_back({s.center, s.radius});
  std::erase_if(casters_, [](const Sphere& s) { return !(s.radius > 0) || !std::isfinite(s.radius) || !is_finite(s.center); });
  // The largest first (a stable sort: ties keep scene order), and at most kMaxCasters of them.
  std::stable_sort(casters_.begin(), casters_.end(), [](const Sphere& a, const Sphere& b) { return a.radius > b.radius; });
  if (casters_.size() > size_t(kMaxCasters)) casters_.resize(size_t(kMaxCasters));
}

void CausticCasters::view(const Vec3& p, const Vec3& n, CasterView& v) const {
  v.count_ = 0;
  for (const Sphere& s : casters_) {
    if (v.count_ == CasterView::kMaxCones) break;
    const Vec3 d = s.center - p;
    const float d2 = length_squared(d);
    const float r2 = s.radius * s.radius;
    // Outside the sphere, a cone under 45 degrees, and some of it above the tangent plane: the
    // cone's axis makes an angle with the plane smaller than its half-angle, dot(n, d) > -r.
    if (!(r2 < kMaxSin2 * d2) || !(dot(n, d) > -s.radius)) continue;
    const float inv_dist = 1.0f / std::sqrt(d2);
    const float sin2 = r2 / d2;
    const float cos_max = std::sqrt(1.0f - sin2);
    const float omc = sin2 / (1.0f + cos_max);
    const int k = v.count_++;
    v.axis_x_[k] = d.x * inv_dist;
    v.axis_y_[k] = d.y * inv_dist;
    v.axis_z_[k] = d.z * inv_dist;
    v.cos_max_[k] = cos_max;
    v.one_minus_cos_max_[k] = omc;
    v.density_[k] = 1.0f / (kTwoPi * omc);
  }
}

Vec3 CasterView::sample(float u_pick, Vec2 u_dir) const {
  const int k = std::min(int(u_pick * float(count_)), count_ - 1);
  const Vec3 axis(axis_x_[k], axis_y_[k], axis_z_[k]);
  return normalize(Frame::from_normal(axis).to_world(sample_uniform_cone(u_dir, one_minus_cos_max_[k])));
}

float CasterView::pdf(const Vec3& w) const {
  float sum = 0;
  for (int k = 0; k < count_; ++k)
    if (w.x * axis_x_[k] + w.y * axis_y_[k] + w.z * axis_z_[k] >= cos_max_[k]) sum += density_[k];
  return count_ > 0 ? sum / float(count_) : 0.0f;
}

}  // namespace prism
