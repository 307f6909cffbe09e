// LaneVertexBatch, lane_vertices: Lambertian and coated vertices' next-event estimation and bounce in SIMD lanes.
#pragma once

#include "core/emitters.h"
#include "core/ray.h"
#include "core/vec3.h"
#include "integrators/lane_bounce.h"
#include "integrators/lane_coated_lobe.h"
#include "integrators/lane_direct_light.h"
#include "integrators/lane_lambertian_lobe.h"

namespace prism {

// A vertex's fields; rows of three hold a vector's x, y and z. The surface's come first
// (LambertianSurfaceFields), then the light request's, then the bounce's, then those of a light
// sample toward a direction, then a coated surface's mixture (kCoatAlpha 0: the Lambertian lobe
// alone). A triangle light's own constants are not among them: each lane points at its light's
// record (Emitters::LaneRecord).
struct LaneVertexFields : LambertianSurfaceFields {
  enum Row {
    kBeta = kSurfaceRows,  // three rows, one each below
    kLightUx = kBeta + 3, kLightUy, kPmf, kWantsLight, kBounceUx, kBounceUy, kWantsBounce,
    kTowardW, kIncident = kTowardW + 3, kTowardDistance = kIncident + 3, kTowardPdf, kTowardDelta, kWeighLater,
    kCoatAlpha, kCoatEta, kDiffuseAlbedo, kBounceULobe, kMetallic, kBaseColor, kRows = kBaseColor + 3
  };
  // kWantsLight: a point on a triangle light (kLightUx, kLightUy, kPmf and the record), or a
  // direction toward a punctual light or the sky (kTowardW to kTowardDelta); 0: none.
  static constexpr float kOnTriangle = 1, kToward = 2;
};

// Up to kLanes vertices, each asking for its light sample, its bounce, or both: Lambertian ones
// (Bsdf::lambertian_only) and glTF's opaque metallic-roughness mixture (Bsdf::coated_only),
// "coated" here. Light samples outside every volume only: no medium absorbs.
class LaneVertexBatch : public LaneVertexFields, public LambertianLaneRows<LaneVertexFields::kRows> {
 public:
  // A vertex: its surface, its hit's point and the point's error bound. Returns its lane, which asks
  // for nothing yet. At most kLanes.
  int add(const LambertianSurface& surface, const Vec3& p, const Vec3& p_error);
  // A vertex whose Bsdf is the coated mixture (Bsdf::coated_only): `coated`'s metal and layer, and
  // the Lambertian lobe of `surface`.
  int add(const LambertianSurface& surface, const Vec3& p, const Vec3& p_error, const CoatedSurface& coated);
  // The lane's light sample: the triangle its hit is on, the path's throughput, and the light point
  // drawn for it (Emitters::triangle_draw), whose record must outlive the kernel's run.
  void request_light(int lane, TriangleId leaves, const Rgb& beta, const Emitters::TriangleDraw& light);
  // The lane's light sample toward a punctual light or the sky, drawn already (Emitters::sample_light).
  void request_light_toward(int lane, TriangleId leaves, const Rgb& beta, const EmitterSample& light);
  // The lane's light sample, asked for already, is weighed by the caller: its LaneLightResult holds
  // the unweighted contribution and the MIS pieces.
  void weigh_later(int lane) { set(kWeighLater, lane, 1.0f); }
  // The lane's bounce, with its direction and lobe draws (a Lambertian lane ignores the latter).
  void request_bounce(int lane, Vec2 u, float u_lobe);
  TriangleId leaves(int lane) const { return leaves_[lane]; }
  // Whether a lane holds a coated vertex (else the kernels are built without the coated lobes).
  bool has_coated() const { return has_coated_; }
  void clear() {
    LambertianLaneRows::clear();
    has_coated_ = false;
  }
  // The light records of lanes first to first + 7 (zeros where a lane asks for no light).
  const float* const* records(int first) const { return &records_[first]; }

 private:
  TriangleId leaves_[kLanes];
  const float* records_[kLanes];
  bool has_coated_ = false;  // since clear()
};

// For each lane of the batch, the lobe's frame (once), then what it asks for: its light sample's
// shadow ray and contribution (lanes::direct_light) and its bounce (lanes::bounce). A result the
// lane did not ask for is not to be read. In AVX2 where the CPU has it and `avx2` allows it, else
// in SSE pairs (the same bits).
void lane_vertices(const LaneVertexBatch& batch, LaneLightResult* lights, LaneBounce* bounces, bool avx2 = true);

}  // namespace prism
