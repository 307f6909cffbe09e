#include "core/light_bounds.h"

#include <algorithm>
#include <cmath>

#include "core/constants.h"

namespace prism {
namespace {

float safe_sqrt(float x) { return std::sqrt(std::max(0.0f, x)); }
float safe_acos(float x) { return std::acos(std::clamp(x, -1.0f, 1.0f)); }

}  // namespace

DirectionCone cone_union(const DirectionCone& a, const DirectionCone& b) {
  if (a.cos_theta <= -1.0f || b.cos_theta <= -1.0f) return DirectionCone::every_direction();
  if (a.w == b.w) return a.cos_theta <= b.cos_theta ? a : b;  // coplanar emitters, often
  const float theta_a = safe_acos(a.cos_theta), theta_b = safe_acos(b.cos_theta);
  const float theta_d = safe_acos(dot(a.w, b.w));
  if (std::min(theta_d + theta_b, kPi) <= theta_a) return a;
  if (std::min(theta_d + theta_a, kPi) <= theta_b) return b;
  // The union's half-angle spans both cones along the great circle through their axes; its axis
  // is a.w turned toward b.w by theta_o - theta_a.
  const float theta_o = 0.5f * (theta_a + theta_d + theta_b);
  if (theta_o >= kPi) return DirectionCone::every_direction();
  const Vec3 toward_b = b.w - a.w * dot(a.w, b.w);
  const float len = length(toward_b);
  if (!(len > 0)) return DirectionCone::every_direction();  // opposite axes
  const float turn = theta_o - theta_a;
  const Vec3 w = normalize(a.w * std::cos(turn) + toward_b * (std::sin(turn) / len));
  return {w, std::cos(theta_o)};
}

LightBounds merge(const LightBounds& a, const LightBounds& b,
                  DirectionCone (*cones)(const DirectionCone&, const DirectionCone&)) {
  if (!(a.power > 0)) return b;
  if (!(b.power > 0)) return a;
  LightBounds m;
  m.box = a.box;
  m.box.extend(b.box);
  m.normals = cones(a.normals, b.normals);
  m.cos_emit = std::min(a.cos_emit, b.cos_emit);
  m.power = a.power + b.power;
  m.two_sided = a.two_sided || b.two_sided;
  return m;
}

float orientation_measure(const LightBounds& b) {
  // Angles from their cosines with a polynomial acos (Abramowitz & Stegun 4.4.45, within 7e-5
  // rad), and the cosine of theta_o - 2 theta_w by angle-sum identities: the split search calls
  // this for every candidate plane, and only compares the results.
  auto acos_approx = [](float x) {
    const float a = std::min(std::abs(x), 1.0f);
    const float r = std::sqrt(1.0f - a) * (1.5707288f + a * (-0.2121144f + a * (0.0742610f - 0.0187293f * a)));
    return x < 0 ? kPi - r : r;
  };
  const float cos_o = std::clamp(b.normals.cos_theta, -1.0f, 1.0f), sin_o = safe_sqrt(1.0f - cos_o * cos_o);
  const float cos_e = std::clamp(b.cos_emit, -1.0f, 1.0f), sin_e = safe_sqrt(1.0f - cos_e * cos_e);
  const float theta_o = acos_approx(cos_o);
  float theta_w = kPi, cos_w = -1.0f, sin_w = 0.0f;  // theta_w = min(theta_o + theta_e, pi)
  if (cos_o > -cos_e) {
    theta_w = theta_o + acos_approx(cos_e);
    cos_w = cos_o * cos_e - sin_o * sin_e;
    sin_w = sin_o * cos_e + cos_o * sin_e;
  }
  const float cos_2w = cos_w * cos_w - sin_w * sin_w, sin_2w = 2.0f * sin_w * cos_w;
  const float cos_o_minus_2w = cos_o * cos_2w + sin_o * sin_2w;
  return kTwoPi * (1.0f - cos_o) +
         kPiOver2 * (2.0f * theta_w * sin_o - cos_o_minus_2w - 2.0f * theta_o * sin_o + cos_o);
}

}  // namespace prism
