#include "integrators/lane_vertices.h"

namespace prism {
namespace {

// Lanes first to first + 7: the lobe's frame, shared by the light sample and the bounce.
struct Results {
  LaneLightResult* lights;
  LaneBounce* bounces;
};
[[gnu::always_inline]] inline void eight_lanes(const LaneVertexBatch& batch, int first, const Results* out) {
  using namespace lanes;
  const Lobe lobe = lambertian_lobe(batch, first);
  if (any(row(batch, LaneVertexBatch::kWantsLight, first) != 0)) direct_light(batch, first, lobe, out->lights);
  if (any(row(batch, LaneVertexBatch::kWantsBounce, first) != 0)) bounce(batch, first, lobe, out->bounces);
}

}  // namespace

int LaneVertexBatch::add(const LambertianSurface& surface, const Vec3& p, const Vec3& p_error) {
  const int lane = add_surface(surface, p, p_error);
  set(kWantsLight, lane, 0.0f);
  set(kWantsBounce, lane, 0.0f);
  return lane;
}

void LaneVertexBatch::request_light(int lane, TriangleId leaves, const Rgb& beta, const Emitters::TriangleDraw& light,
                                    const Rgb& emission, bool double_sided) {
  leaves_[lane] = leaves;
  set(kWantsLight, lane, 1.0f);
  set(kBeta, lane, beta);
  const Emitters::Emitter& e = *light.light;
  set(kP0, lane, e.p0);
  set(kP1, lane, e.p1);
  set(kP2, lane, e.p2);
  set(kP3, lane, e.p3);
  set(kLightUx, lane, light.u.x);
  set(kLightUy, lane, light.u.y);
  set(kNear, lane, light.near ? 1.0f : 0.0f);
  set(kQuad, lane, e.quad ? 1.0f : 0.0f);
  set(kHalf, lane, float(light.half));
  set(kB0, lane, light.b.b0);
  set(kB1, lane, light.b.b1);
  set(kB2, lane, light.b.b2);
  set(kLightN, lane, e.normal);
  set(kSlack, lane, e.quad_slack);
  set(kPdfArea, lane, 1.0f / e.area);
  set(kPmf, lane, light.pmf);
  set(kEmission, lane, emission);
  set(kDoubleSided, lane, double_sided ? 1.0f : 0.0f);
}

void LaneVertexBatch::request_bounce(int lane, Vec2 u) {
  set(kWantsBounce, lane, 1.0f);
  set(kBounceUx, lane, u.x);
  set(kBounceUy, lane, u.y);
}

void lane_vertices(const LaneVertexBatch& batch, LaneLightResult* lights, LaneBounce* bounces, bool avx2) {
  const Results out{lights, bounces};
  lanes::run_lanes<eight_lanes>(batch, &out, avx2);
}

}  // namespace prism
