#include "core/light_importance.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace prism {

LightImportance::LightImportance(const LightBounds& b, double power_scale) {
  const Vec3 c = b.box.center();
  const float radius = 0.5f * length(b.box.diagonal());
  terms_.center_x = c.x;
  terms_.center_y = c.y;
  terms_.center_z = c.z;
  terms_.radius = radius;
  terms_.axis_x = b.normals.w.x;
  terms_.axis_y = b.normals.w.y;
  terms_.axis_z = b.normals.w.z;
  terms_.cos_o = b.normals.cos_theta;
  terms_.sin_o = std::sqrt(std::max(0.0f, 1.0f - b.normals.cos_theta * b.normals.cos_theta));
  terms_.cos_emit = b.cos_emit;
  terms_.two_sided = b.two_sided ? 1.0f : 0.0f;
  terms_.inv_radius2 = 1.0f / std::max(radius * radius, std::numeric_limits<float>::min());
  terms_.power = b.power > 0 ? static_cast<float>(b.power * power_scale) : 0.0f;
}

void LightImportance4::set(int lane, const LightImportance& group) {
  for_each_term([lane](Float4& lanes, float one) { lanes.set_lane(lane, one); }, terms_, group.terms());
}

// flatten inlines importance_at and the Float8 operations here, where they compile to AVX
// instructions; compiled anywhere else they would be pairs of SSE ones.
__attribute__((target("avx2"), flatten)) float evaluate_pair(const LightImportance4& lo, const LightImportance4& hi,
                                                           const Vec3& p, const Vec3& n, float out[8]) {
  ImportanceTerms<Float8> t;
  for_each_term([](Float8& eight, Float4 four_lo, Float4 four_hi) { eight = Float8(four_lo, four_hi); }, t, lo.terms(),
                hi.terms());
  const Float8 r = importance_at(t, p, n);
  std::memcpy(out, &r.v, sizeof r.v);
  // Neighbours added in lanes 0, 2, 4, 6, then neighbouring pairs in lanes 0 and 4.
  const Float8Lanes pairs = r.v + __builtin_shufflevector(r.v, r.v, 1, 0, 3, 2, 5, 4, 7, 6);
  const Float8Lanes fours = pairs + __builtin_shufflevector(pairs, pairs, 2, 3, 0, 1, 6, 7, 4, 5);
  return fours[0] + fours[4];
}

}  // namespace prism
