#include "core/caustic_casters.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/constants.h"
#include "core/float8.h"
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
    cx_[size_t(count_)] = c.center.x;
    cy_[size_t(count_)] = c.center.y;
    cz_[size_t(count_)] = c.center.z;
    radius_[size_t(count_)] = c.radius;
    ++count_;
  }
}

// The kMaxCasters slots are the eight lanes of one Float8 (core/float8.h): each lane rounds as the
// formula for one slot would, so the view is the one a loop over the slots makes, bit for bit.
static_assert(CausticCasters::kMaxCasters == 8, "view and pdf take the slots as the eight lanes of a Float8");

void CausticCasters::view(const Vec3& p, const Vec3& n, CasterView& v) const {
  const Float8 dx = load8(cx_.data()) - Float8(p.x), dy = load8(cy_.data()) - Float8(p.y),
               dz = load8(cz_.data()) - Float8(p.z);
  const Float8 d2 = dx * dx + dy * dy + dz * dz;
  const Float8 r = load8(radius_.data()), r2 = r * r;
  const Float8 raw_sin2 = r2 / d2;  // +inf at the centre itself, 0 (NaN where p is the origin) in an empty slot
  // Outside the sphere, a cone between a microradian and 45 degrees, and some of it above the
  // tangent plane: the axis's angle with the plane is under the half-angle, dot(n, d) > -r.
  const Mask8 aimed = both(both(raw_sin2 < Float8(kMaxSin2), raw_sin2 > Float8(kMinSin2)),
                           dx * Float8(n.x) + dy * Float8(n.y) + dz * Float8(n.z) > Float8(0.0f) - r);
  const Float8 sin2 = select(aimed, raw_sin2, Float8(kMaxSin2));  // kMaxSin2 keeps the arithmetic finite
  const Float8 omc = sin2 / (Float8(1.0f) + vsqrt(Float8(1.0f) - sin2));
  store8(v.dx_, dx);
  store8(v.dy_, dy);
  store8(v.dz_, dz);
  store8(v.edge_, d2 - r2);
  store8(v.one_minus_cos_max_, omc);
  store8(v.density_, select(aimed, Float8(1.0f) / (Float8(kTwoPi) * omc), Float8(0.0f)));
  float aimed_sin2[kMaxCasters];  // sin^2 of an aimed cone's half-angle, else 0
  store8(aimed_sin2, select(aimed, sin2, Float8(0.0f)));
  float coverage = 0;
  for (int k = 0; k < kMaxCasters; ++k) coverage += aimed_sin2[k];  // in slot order; the empty slots add +0
  v.slots_ = count_;
  v.count_ = count_lanes(aimed);
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
  const Float8 t = Float8(w.x) * load8(dx_) + Float8(w.y) * load8(dy_) + Float8(w.z) * load8(dz_);
  const Mask8Lanes slot{0, 1, 2, 3, 4, 5, 6, 7};
  const Mask8 in_cone = both(t > Float8(0.0f), t * t >= load8(edge_));
  const Mask8 inside{(slot == (Mask8Lanes{} + drawn_in)) | in_cone.v};
  float density[kMaxCasters];  // the cones' terms, summed in slot order
  store8(density, select(inside, load8(density_), Float8(0.0f)));
  float sum = 0;
  for (int k = 0; k < kMaxCasters; ++k) sum += density[k];  // the empty slots' densities are +0
  return count_ > 0 ? sum / float(count_) : 0.0f;
}

}  // namespace prism
