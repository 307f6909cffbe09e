#include "integrators/lane_vertices.h"

#include <algorithm>

namespace prism {
namespace {

struct Results {
  LaneLightResult* lights;
  LaneBounce* bounces;
};

// Lanes first to first + 7: the lobe's frame, shared by the light samples and the bounces, then
// each where a lane of the eight asks for it.
// kCoated: the batch may hold coated lanes; without them the coated lobes are left out.
template <bool kCoated>
[[gnu::always_inline]] inline void eight_lanes(const LaneVertexBatch& batch, int first, const Results* out) {
  using namespace lanes;
  const Lobe lobe = lambertian_lobe(batch, first);
  Coats coats{};
  if constexpr (kCoated) coats = coats_of(batch, first, lobe);
  const F8 light = row(batch, LaneVertexBatch::kWantsLight, first);
  // Toward a direction second: it writes its own lanes' results only, over what the first left there.
  if (any(light == LaneVertexBatch::kOnTriangle)) direct_light<kCoated>(batch, first, lobe, coats, out->lights);
  if (any(light == LaneVertexBatch::kToward)) direct_light_toward<kCoated>(batch, first, lobe, coats, out->lights);
  if (any(row(batch, LaneVertexBatch::kWantsBounce, first) != 0))
    bounce<kCoated>(batch, first, lobe, coats, out->bounces);
}

const Emitters::LaneRecord kNoLight;  // the record of a lane that asks for no light

}  // namespace

int LaneVertexBatch::add(const LambertianSurface& surface, const Vec3& p, const Vec3& p_error) {
  const int lane = add_surface(surface, p, p_error);
  set(kWantsLight, lane, 0.0f);
  set(kWantsBounce, lane, 0.0f);
  set(kWeighLater, lane, 0.0f);
  set(kCoatAlpha, lane, 0.0f);
  // The kernel reads its block's eight records: those of lanes not (yet) asking for a light are zeros.
  if (lane % lanes::kLanes == 0) std::fill_n(&records_[lane], lanes::kLanes, kNoLight.v);
  records_[lane] = kNoLight.v;
  return lane;
}

int LaneVertexBatch::add(const LambertianSurface& surface, const Vec3& p, const Vec3& p_error,
                         const CoatedSurface& coated) {
  const int lane = add(surface, p, p_error);
  has_coated_ = true;
  set(kCoatAlpha, lane, coated.alpha);  // at least GgxDistribution::kSmoothAlpha (Bsdf::coated_only): never 0
  set(kCoatEta, lane, coated.eta);
  set(kDiffuseAlbedo, lane, coated.diffuse_albedo);
  set(kMetallic, lane, coated.metallic);
  set(kBaseColor, lane, coated.base_color);
  return lane;
}

void LaneVertexBatch::request_light(int lane, TriangleId leaves, const Rgb& beta, const Emitters::TriangleDraw& light) {
  leaves_[lane] = leaves;
  records_[lane] = light.record->v;
  set(kWantsLight, lane, kOnTriangle);
  set(kBeta, lane, beta);
  set(kLightUx, lane, light.u.x);
  set(kLightUy, lane, light.u.y);
  set(kPmf, lane, light.pmf);
}

void LaneVertexBatch::request_light_toward(int lane, TriangleId leaves, const Rgb& beta, const EmitterSample& light) {
  leaves_[lane] = leaves;
  set(kWantsLight, lane, kToward);
  set(kBeta, lane, beta);
  set(kTowardW, lane, light.wi);
  set(kIncident, lane, light.incident);
  set(kTowardDistance, lane, light.distance);
  set(kTowardPdf, lane, light.pdf);
  set(kTowardDelta, lane, light.delta ? 1.0f : 0.0f);
}

void LaneVertexBatch::request_bounce(int lane, Vec2 u, float u_lobe) {
  set(kWantsBounce, lane, 1.0f);
  set(kBounceUx, lane, u.x);
  set(kBounceUy, lane, u.y);
  set(kBounceULobe, lane, u_lobe);
}

void lane_vertices(const LaneVertexBatch& batch, LaneLightResult* lights, LaneBounce* bounces, bool avx2) {
  const Results out{lights, bounces};
  if (batch.has_coated())
    lanes::run_lanes<eight_lanes<true>>(batch, &out, avx2);
  else
    lanes::run_lanes<eight_lanes<false>>(batch, &out, avx2);
}

}  // namespace prism
