// CausticCasters: the smooth or glossy metal and smooth glass objects of a scene, as bounding spheres
// a path can aim its bounce directions at, so that light reaching a diffuse surface through them is found.
#pragma once

#include <array>
#include <vector>

#include "core/scene_desc.h"

namespace prism {

// The casters seen from one shading point: a cone of directions for each caster that is worth
// aiming at from there. Directions are drawn by choosing one of the cones uniformly, then a
// direction uniformly inside it; pdf() is the density of that draw over all the cones.
class CasterView {
 public:
  static constexpr int kMaxCasters = 8;

  // Empty. User-provided, so that a view made at every vertex does not zero its arrays first.
  CasterView() {}

  bool empty() const { return count_ == 0; }
  int size() const { return count_; }  // the cones
  // u_pick chooses the cone (its slot goes to *cone), u_dir the direction in it; the result is a
  // unit vector.
  Vec3 sample(float u_pick, Vec2 u_dir, int* cone = nullptr) const;
  // Solid-angle density of sample() drawing unit direction w. drawn_in: the slot of the cone
  // sample() drew w in, counted as holding it even where rounding puts w a hair outside its rim
  // (that cone's density then cannot go missing from w's weight).
  float pdf(const Vec3& w, int drawn_in = -1) const;
  // How much of the view the casters fill: the sum of sin^2 of the cones' half-angles (a small
  // cone's solid angle over pi; overlaps counted twice).
  float coverage() const { return coverage_; }

 private:
  friend class CausticCasters;
  // Slot k holds caster k: the vector d from the shading point to its centre, |d|^2 - r^2 (w is in
  // the cone when dot(w, d) > 0 and dot(w, d)^2 >= that, with no square root), 1 - cos of the
  // half-angle, and the cone's density 1 / solid angle, 0 when the caster is not worth aiming at
  // from here. view() and pdf() take all kMaxCasters slots at once, as SIMD lanes (core/float8.h):
  // the slots past slots_ hold no caster (radius 0), and their density is 0.
  float dx_[kMaxCasters], dy_[kMaxCasters], dz_[kMaxCasters], edge_[kMaxCasters];
  float one_minus_cos_max_[kMaxCasters], density_[kMaxCasters];
  int slots_ = 0;
  int count_ = 0;
  float coverage_ = 0;
};

class CausticCasters {
 public:
  // A caster is a mesh primitive or analytic sphere whose material has a metal lobe of roughness
  // at most kMaxMetalRoughness, or bounds a refracting volume with roughness at most
  // kMaxGlassRoughness (by its factors, or by enough of its texels where a texture scales them):
  // the surfaces that focus light into caustics next-event estimation cannot reach (its shadow
  // rays stop at them). A glossy metal counts too: lit by a small, bright light (a sun), it throws
  // a blurred caustic that only bounce directions find (docs/PERFORMANCE.md, session 36: aiming at
  // a gold block of roughness 0.4 cut hdri-textures' error to 0.59x; at 0.6 to 0.85x, and at 0.8
  // it cost 3%). Thin sheets are not casters: shadow rays cross them (integrators/sheet_crossing.h),
  // and what they reflect is weak. Positions are world space (the instance transforms applied);
  // each caster is bounded by a sphere around its box.
  static constexpr float kMaxMetalRoughness = 0.5f;
  static constexpr float kMaxGlassRoughness = 0.2f;
  // Whether a surface point of these values focuses light as a caster does.
  static bool is_smooth(float metallic, float roughness, bool volume);
  // The largest, by bounding radius, when there are more: each costs every vertex a cone.
  static constexpr int kMaxCasters = CasterView::kMaxCasters;

  CausticCasters() = default;
  explicit CausticCasters(const SceneDesc& desc);

  bool empty() const { return count_ == 0; }
  size_t size() const { return size_t(count_); }
  // The casters worth aiming at from point p on a surface with unit normal n (the side light is
  // reflected to): those whose bounding sphere subtends a cone of half-angle under 45 degrees (a
  // wider cone is found often enough by the BSDF's own samples, and p is outside the sphere) and
  // that rise above the surface's tangent plane.
  void view(const Vec3& p, const Vec3& n, CasterView& out) const;

  // Whether a material's surfaces are casters: with a metallic-roughness texture, when at least
  // 1 / kMinSmoothFraction of its texels are (aimed directions that meet the rest are not lost,
  // MIS weighs them, but they seldom lead to a caustic).
  static bool is_caster(const SceneDesc& desc, const MaterialDesc& m);
  static constexpr int kMinSmoothFraction = 4;

 private:
  // Each caster's bounding sphere, by component for view()'s vectorised loop; the slots past
  // count_ are zeros, which no view aims at.
  std::array<float, kMaxCasters> cx_{}, cy_{}, cz_{}, radius_{};
  int count_ = 0;
};

}  // namespace prism
