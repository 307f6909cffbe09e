#include "core/environment_portals.h"

#include <cmath>
#include <new>

namespace prism {
namespace {

// Whether the ray from o along w crosses triangle (p0, p1, p2) (Moller and Trumbore 1997).
bool crosses(const Vec3& o, const Vec3& w, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  const Vec3 pv = cross(w, e2);
  const float det = dot(e1, pv);
  if (det == 0) return false;
  const float inv = 1.0f / det;
  const Vec3 tv = o - p0;
  const float b1 = dot(tv, pv) * inv;
  if (b1 < 0 || b1 > 1) return false;
  const Vec3 qv = cross(tv, e1);
  const float b2 = dot(w, qv) * inv;
  if (b2 < 0 || b1 + b2 > 1) return false;
  return dot(e2, qv) * inv > 0;
}

}  // namespace

EnvironmentPortals::EnvironmentPortals(const SceneDesc& desc) {
  // A corner's index, added where no earlier triangle has the very same point.
  const auto corner = [&](const Vec3& p) {
    for (size_t i = 0; i < corners_.size(); ++i)
      if (corners_[i] == p) return int(i);
    corners_.push_back(p);
    return int(corners_.size() - 1);
  };
  for (const InstanceDesc& inst : desc.instances) {
    for (const PrimitiveDesc& prim : desc.meshes[size_t(inst.mesh)].primitives) {
      if (!desc.material(prim.material).is_thin_sheet()) continue;
      for (size_t t = 0; t < prim.triangle_count(); ++t) {
        if (triangles_.size() == size_t(kMaxTriangles)) {
          triangles_.clear();
          corners_.clear();
          return;
        }
        const int c0 = corner(world_corner(inst, prim, t, 0));
        const int c1 = corner(world_corner(inst, prim, t, 1));
        triangles_.push_back({c0, c1, corner(world_corner(inst, prim, t, 2))});
      }
    }
  }
}

EnvironmentPortals::View EnvironmentPortals::view(const Vec3& ref) const {
  View v;
  for (size_t i = 0; i < corners_.size(); ++i) v.set_corner(i, SphericalTriangle::see(ref, corners_[i]));
  for (size_t i = 0; i < triangles_.size(); ++i) {
    const Triangle& t = triangles_[i];
    const float omega = SphericalTriangle::solid_angle(v.corner(t.c0), v.corner(t.c1), v.corner(t.c2));
    v.solid_angle[i] = 0;
    if (omega >= kMinSolidAngle && std::isfinite(omega)) {
      v.solid_angle[i] = omega;
      v.total += omega;
    }
  }
  return v;
}

std::optional<EnvironmentPortals::Sample> EnvironmentPortals::sample(const View& view, const Vec3& ref, Vec2 u) const {
  if (!(view.total > 0)) return std::nullopt;
  // The triangle by u.x, which rescaled within its share then serves the direction.
  float target = u.x * view.total, start = 0;
  size_t chosen = triangles_.size();
  for (size_t i = 0; i < triangles_.size(); ++i) {
    if (view.solid_angle[i] == 0) continue;
    chosen = i;
    if (target < start + view.solid_angle[i]) break;
    start += view.solid_angle[i];
  }
  if (chosen == triangles_.size()) return std::nullopt;
  u.x = std::fmin(std::fmax((target - start) / view.solid_angle[chosen], 0.0f), 0x1.fffffep-1f);
  const Triangle& t = triangles_[chosen];
  const SphericalTriangle::Corner &c0 = view.corner(t.c0), &c1 = view.corner(t.c1), &c2 = view.corner(t.c2);
  const std::optional<Barycentrics> b = SphericalTriangle(ref, c0, c1, c2, view.solid_angle[chosen]).sample(u);
  if (!b) return std::nullopt;
  const Vec3 d = c0.p * b->b0 + c1.p * b->b1 + c2.p * b->b2 - ref;
  const float len = length(d);
  if (!(len > 0)) return std::nullopt;
  return Sample{d / len, int(chosen)};
}

float EnvironmentPortals::pdf(const View& view, const Vec3& ref, const Vec3& w, int drawn_in) const {
  if (!(view.total > 0)) return 0;
  int crossed = 0;
  for (size_t i = 0; i < triangles_.size(); ++i) {
    const Triangle& t = triangles_[i];
    if (view.solid_angle[i] > 0 &&
        (int(i) == drawn_in || crosses(ref, w, corners_[size_t(t.c0)], corners_[size_t(t.c1)], corners_[size_t(t.c2)])))
      ++crossed;
  }
  return float(crossed) / view.total;
}

}  // namespace prism
