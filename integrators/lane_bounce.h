// LaneBounceBatch, lane_bounce: the Lambertian lobe's cosine-weighted bounce and the next ray's origin, in SIMD lanes.
#pragma once

#include "core/vec3.h"
#include "integrators/lane_lambertian_lobe.h"

namespace prism {

// A bounce request's fields; rows of three hold a vector's x, y and z.
struct LaneBounceFields : LambertianSurfaceFields {
  enum Row { kUx = kSurfaceRows, kUy, kRows };
};

// Up to kLanes Lambertian vertices' bounces.
class LaneBounceBatch : public LaneBounceFields, public LambertianLaneRows<LaneBounceFields::kRows> {
 public:
  // A vertex: its surface, its point and the point's error bound, and its direction draw. Returns
  // its lane. At most kLanes.
  int add(const LambertianSurface& surface, const Vec3& p, const Vec3& p_error, Vec2 u);
};

// What Bsdf::sample gives for the vertex's Lambertian lobe (sampled false where it gives nothing),
// and the origin spawn_ray would give the ray leaving the hit along wi.
struct LaneBounce {
  Vec3 wi, origin;
  Rgb f_cos;
  float pdf = 0;
  bool sampled = false;
};

// Each lane's bounce, bit for bit what Bsdf::sample and spawn_ray make of it. In AVX2 where the CPU
// has it and `avx2` allows it, else in SSE pairs (the same bits).
void lane_bounce(const LaneBounceBatch& batch, LaneBounce* out, bool avx2 = true);

}  // namespace prism
