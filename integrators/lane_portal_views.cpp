#include "integrators/lane_portal_views.h"

#include <cstring>

#include "core/cpu_features.h"
#include "integrators/lane_spherical_triangle.h"

namespace prism {
namespace {

using namespace lanes;

[[gnu::always_inline]] inline V8 splat(const Vec3& v) {
  return {lanes::splat(v.x), lanes::splat(v.y), lanes::splat(v.z)};
}

// EnvironmentPortals::view's steps, lane k for refs[k]: the corners in order, then the triangles'
// solid angles summed in order (a left-out triangle adds nothing: total + 0 is total's bits).
[[gnu::always_inline]] inline void views8(const EnvironmentPortals& portals, const Vec3* refs, int n,
                                          EnvironmentPortals::View* out) {
  alignas(32) float x[kLanes], y[kLanes], z[kLanes];
  for (int k = 0; k < kLanes; ++k) {  // lanes past n repeat the first point; their views are not kept
    const Vec3& r = refs[k < n ? k : 0];
    x[k] = r.x;
    y[k] = r.y;
    z[k] = r.z;
  }
  const V8 ref{load(x, 0), load(y, 0), load(z, 0)};
  const std::vector<Vec3>& corners = portals.corners();
  // The first corners seen are kept for the triangles (a pane's four corners, a few panes'); any
  // further ones are seen again there, to the same bits.
  constexpr size_t kKept = 16;
  Corner8 seen[kKept];
  for (size_t i = 0; i < corners.size(); ++i) {
    const Corner8 c = see(ref, splat(corners[i]));
    if (i < kKept) seen[i] = c;
    // Lane k's Corner (p, dir, distance, inverse_distance: eight floats) by one 8x8 transpose.
    const F8 fields[8] = {c.p.x, c.p.y, c.p.z, c.dir.x, c.dir.y, c.dir.z, c.distance, c.inverse_distance};
    const float* records[8];
    for (int f = 0; f < 8; ++f) records[f] = reinterpret_cast<const float*>(&fields[f]);
    F8 per_lane[8];
    transpose(records, 0, per_lane);
    for (int k = 0; k < n; ++k) {
      SphericalTriangle::Corner corner;
      static_assert(sizeof corner == sizeof(F8));
      std::memcpy(&corner, &per_lane[k], sizeof corner);
      out[k].set_corner(i, corner);
    }
  }
  const auto corner = [&](int i) { return size_t(i) < kKept ? seen[i] : see(ref, splat(corners[size_t(i)])); };
  F8 total = lanes::splat(0.0f);
  const std::vector<EnvironmentPortals::Triangle>& triangles = portals.triangles();
  for (size_t t = 0; t < triangles.size(); ++t) {
    const EnvironmentPortals::Triangle& tri = triangles[t];
    const F8 omega = solid_angle(corner(tri.c0), corner(tri.c1), corner(tri.c2));
    // omega is finite here (solid_angle gives 0 otherwise).
    const F8 kept = pick(omega >= EnvironmentPortals::kMinSolidAngle, omega, lanes::splat(0.0f));
    total = total + kept;
    alignas(32) float o[kLanes];
    store(kept, o);
    for (int k = 0; k < n; ++k) out[k].solid_angle[t] = o[k];
  }
  alignas(32) float o[kLanes];
  store(total, o);
  for (int k = 0; k < n; ++k) out[k].total = o[k];
}

__attribute__((target("avx2"), flatten)) void views_avx2(const EnvironmentPortals& portals, const Vec3* refs, int n,
                                                         EnvironmentPortals::View* out) {
  views8(portals, refs, n, out);
}
[[gnu::flatten]] void views_sse(const EnvironmentPortals& portals, const Vec3* refs, int n,
                                EnvironmentPortals::View* out) {
  views8(portals, refs, n, out);
}

}  // namespace

void portal_views(const EnvironmentPortals& portals, const Vec3* refs, int n, EnvironmentPortals::View* out,
                  bool avx2) {
  if (n <= 0) return;
  if (avx2 && cpu_has_avx2())
    views_avx2(portals, refs, n, out);
  else
    views_sse(portals, refs, n, out);
}

}  // namespace prism
