#include "core/light_importance.h"

#include <algorithm>
#include <cmath>
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
  const ImportanceTerms<float>& t = group.terms();
  ImportanceTerms<Float4>& l = terms_;
  l.center_x.set_lane(lane, t.center_x);
  l.center_y.set_lane(lane, t.center_y);
  l.center_z.set_lane(lane, t.center_z);
  l.radius.set_lane(lane, t.radius);
  l.axis_x.set_lane(lane, t.axis_x);
  l.axis_y.set_lane(lane, t.axis_y);
  l.axis_z.set_lane(lane, t.axis_z);
  l.cos_o.set_lane(lane, t.cos_o);
  l.sin_o.set_lane(lane, t.sin_o);
  l.cos_emit.set_lane(lane, t.cos_emit);
  l.two_sided.set_lane(lane, t.two_sided);
  l.inv_radius2.set_lane(lane, t.inv_radius2);
  l.power.set_lane(lane, t.power);
}

}  // namespace prism
