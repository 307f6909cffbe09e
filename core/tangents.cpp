#include "core/tangents.h"

#include <cmath>

#include "core/frame.h"

namespace prism {

TangentFrame triangle_tangent_frame(const Vec3& p0, const Vec3& p1, const Vec3& p2, Vec2 t0, Vec2 t1, Vec2 t2) {
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  const float du1 = t1.x - t0.x, dv1 = t1.y - t0.y, du2 = t2.x - t0.x, dv2 = t2.y - t0.y;
  const float det = du1 * dv2 - du2 * dv1;
  TangentFrame f;
  if (!(std::abs(det) > 1e-20f) || !std::isfinite(det)) return f;
  const float r = 1.0f / det;
  // Solve e = dP/du du + dP/dv dv for both edges.
  f.tangent = (e1 * dv2 - e2 * dv1) * r;
  f.up_image = -((e2 * du1 - e1 * du2) * r);
  f.valid = is_finite(f.tangent) && is_finite(f.up_image) && length_squared(f.tangent) > 0;
  return f;
}

void generate_tangents(PrimitiveDesc& prim) {
  const size_t n = prim.positions.size();
  if (prim.normals.size() != n || prim.uvs.size() != n) return;
  std::vector<Vec3> t(n, Vec3(0.0f)), b(n, Vec3(0.0f));
  for (size_t k = 0; k + 2 < prim.indices.size(); k += 3) {
    const uint32_t i0 = prim.indices[k], i1 = prim.indices[k + 1], i2 = prim.indices[k + 2];
    const TangentFrame f = triangle_tangent_frame(prim.positions[i0], prim.positions[i1], prim.positions[i2],
                                                  prim.uvs[i0], prim.uvs[i1], prim.uvs[i2]);
    if (!f.valid) continue;
    // Unnormalised sums weight each triangle by its area in uv-to-world scale.
    const Vec3 tn = normalize(f.tangent), bn = normalize(f.up_image);
    for (uint32_t i : {i0, i1, i2}) {
      t[i] += tn;
      b[i] += bn;
    }
  }
  prim.tangents.resize(n);
  prim.tangent_signs.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3 nrm = length_squared(prim.normals[i]) > 0 ? normalize(prim.normals[i]) : Vec3(0, 0, 1);
    Vec3 tan = t[i] - nrm * dot(nrm, t[i]);
    if (!(length_squared(tan) > 1e-20f)) tan = Frame::from_normal(nrm).s;
    tan = normalize(tan);
    prim.tangents[i] = tan;
    prim.tangent_signs[i] = dot(cross(nrm, tan), b[i]) < 0 ? -1.0f : 1.0f;
  }
}

}  // namespace prism
