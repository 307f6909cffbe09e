#include "core/caustic_casters.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/constants.h"
#include "core/frame.h"
#include "core/sampling.h"

namespace prism {
namespace {

// A cone wider than 45 degrees (sin^2 of its half-angle above 1/2) holds more than 15% of a
// cosine-weighted hemisphere's samples already: aiming at it buys little. One narrower than a
// microradian is not worth a direction either, and its density would overflow.
constexpr float kMaxSin2 = 0.5f, kMinSin2 = 1e-12f;

}  // namespace

bool CausticCasters::is_smooth(float metallic, float roughness, bool volume) {
  return (metallic > 0 && roughness <= kMaxMetalRoughness) || (volume && roughness <= kMaxGlassRoughness);
}

// glTF 2.0 §3.9.2: the texture's B and G channels scale the metallic and roughness factors. Most
// exported assets set both factors to 1 and leave the texture to say where the surface is
// polished metal, so the factors alone would rule out nearly every textured caster (and count a
// texture of no metal at all as one). A grid of at most 64 x 64 texels stands for the image.
bool CausticCasters::is_caster(const SceneDesc& desc, const MaterialDesc& m) {
  const TextureRef& ref = m.metallic_roughness_texture;
  if (!ref.present()) return is_smooth(m.metallic, m.roughness, m.has_volume());
  const ImageDesc& img = desc.images[size_t(desc.textures[size_t(ref.texture)].image)];
  constexpr int kGrid = 64;
  const int step_x = std::max(1, img.width / kGrid), step_y = std::max(1, img.height / kGrid);
  int64_t smooth = 0, seen = 0;
  for (int y = step_y / 2; y < img.height; y += step_y)
    for (int x = step_x / 2; x < img.width; x += step_x) {
      const Rgb t = img.texel(x, y).rgb;
      smooth += is_smooth(m.metallic * t.z, m.roughness * t.y, m.has_volume());
      ++seen;
    }
  return seen > 0 && smooth * kMinSmoothFraction >= seen;
}

CausticCasters::CausticCasters(const SceneDesc& desc) {
  struct Sphere {
    Vec3 center;
    float radius;
  };
  std::vector<Sphere> casters;
  // Each material judged once (a textured one reads up to 64 x 64 texels), however many primitives
  // and spheres share it; the last slot is the default material's.
  std::vector<int8_t> judged(desc.materials.size() + 1, -1);
  const auto caster = [&](int material) {
    const size_t slot = material >= 0 && size_t(material) < desc.materials.size() ? size_t(material) : judged.size() - 1;
    if (judged[slot] < 0) judged[slot] = is_caster(desc, desc.material(material)) ? 1 : 0;
    return judged[slot] == 1;
  };
  for (const InstanceDesc& inst : desc.instances) {
    for (const PrimitiveDesc& prim : desc.meshes[size_t(inst.mesh)].primitives) {
      if (prim.triangle_count() == 0 || !caster(prim.material)) continue;
      Bounds3 box;
      for (uint32_t i : prim.indices) box.extend(inst.object_to_world.point(prim.positions[i]));
      casters.push_back({(box.lo + box.hi) * 0.5f, 0.5f * length(box.diagonal())});
    }
  }
  for (const SphereDesc& s : desc.spheres)
    if (caster(s.material)) casters.push_back({s.center, s.radius});
  std::erase_if(casters,
                [](const Sphere& s) { return !(s.radius > 0) || !std::isfinite(s.radius) || !is_finite(s.center); });
  // The largest first (a stable sort: ties keep scene order), and at most kMaxCasters of them.
  std::stable_sort(casters.begin(), casters.end(),
                   [](const Sphere& a, const Sphere& b) { return a.radius > b.radius; });
  if (casters.size() > size_t(kMaxCasters)) casters.resize(size_t(kMaxCasters));
  for (const Sphere& c : casters) {
    cx_.push_back(c.center.x);
    cy_.push_back(c.center.y);
    cz_.push_back(c.center.z);
    radius_.push_back(c.radius);
  }
}

void CausticCasters::view(const Vec3& p, const Vec3& n, CasterView& v) const {
  const int slots = static_cast<int>(radius_.size());
  float aimed_sin2[kMaxCasters];  // sin^2 of an aimed cone's half-angle, else 0
  // No sums in this loop (float sums may not be reordered), so that it vectorises.
  for (int k = 0; k < slots; ++k) {
    const float dx = cx_[k] - p.x, dy = cy_[k] - p.y, dz = cz_[k] - p.z;
    const float d2 = dx * dx + dy * dy + dz * dz;
    const float r = radius_[k], r2 = r * r;
    const float raw_sin2 = r2 / d2;  // +inf at the centre itself: not aimed
    // Outside the sphere, a cone between a microradian and 45 degrees, and some of it above the
    // tangent plane: the axis's angle with the plane is under the half-angle, dot(n, d) > -r.
    const bool aimed = raw_sin2 < kMaxSin2 && raw_sin2 > kMinSin2 && dx * n.x + dy * n.y + dz * n.z > -r;
    const float sin2 = aimed ? raw_sin2 : kMaxSin2;  // kMaxSin2 keeps the arithmetic finite
    const float omc = sin2 / (1.0f + std::sqrt(1.0f - sin2));
    v.dx_[k] = dx;
    v.dy_[k] = dy;
    v.dz_[k] = dz;
    v.edge_[k] = d2 - r2;
    v.one_minus_cos_max_[k] = omc;
    v.density_[k] = aimed ? 1.0f / (kTwoPi * omc) : 0.0f;
    aimed_sin2[k] = aimed ? sin2 : 0.0f;
  }
  int count = 0;
  float coverage = 0;
  for (int k = 0; k < slots; ++k) {
    count += aimed_sin2[k] > 0 ? 1 : 0;
    coverage += aimed_sin2[k];
  }
  v.slots_ = slots;
  v.count_ = count;
  v.coverage_ = coverage;
}

Vec3 CasterView::sample(float u_pick, Vec2 u_dir, int* cone) const {
  // The j-th of the slots that hold a cone.
  int j = std::min(int(u_pick * float(count_)), count_ - 1), k = 0;
  for (; k < slots_; ++k)
    if (density_[k] > 0 && j-- == 0) break;
  if (cone) *cone = k;
  const Vec3 axis = normalize(Vec3(dx_[k], dy_[k], dz_[k]));
  return normalize(Frame::from_normal(axis).to_world(sample_uniform_cone(u_dir, one_minus_cos_max_[k])));
}

float CasterView::pdf(const Vec3& w, int drawn_in) const {
  float density[kMaxCasters];  // the cones' terms, summed after the loop so that it vectorises
  for (int k = 0; k < slots_; ++k) {
    const float t = w.x * dx_[k] + w.y * dy_[k] + w.z * dz_[k];
    const bool inside = k == drawn_in || (t > 0 && t * t >= edge_[k]);
    density[k] = inside ? density_[k] : 0.0f;
  }
  float sum = 0;
  for (int k = 0; k < slots_; ++k) sum += density[k];
  return count_ > 0 ? sum / float(count_) : 0.0f;
}

}  // namespace prism
