// LaneLightBatch, lane_direct_light: next-event estimation at Lambertian vertices toward area-drawn points, in lanes.
#pragma once

#include "core/emitters.h"
#include "core/ray.h"
#include "core/vec3.h"
#include "integrators/lane_lambertian_lobe.h"

namespace prism {

// A light request's fields; rows of three hold a vector's x, y and z.
struct LaneLightFields : LambertianSurfaceFields {
  enum Row {
    kBeta = kSurfaceRows, kP0 = kBeta + 3, kP1 = kP0 + 3, kP2 = kP1 + 3, kP3 = kP2 + 3, kLightN = kP3 + 3,
    kEmission = kLightN + 3,  // the rows of three above, one each below
    kUx = kEmission + 3, kUy, kNear, kQuad, kHalf, kB0, kB1, kB2, kSlack, kPdfArea, kPmf, kDoubleSided, kRows
  };
};

// Up to kLanes vertices' light requests. Outside every volume only: no medium absorbs.
class LaneLightBatch : public LaneLightFields, public LambertianLaneRows<LaneLightFields::kRows> {
 public:
  // A vertex: its surface, its hit's point, the point's error bound and triangle, and the path's
  // throughput, with the light point drawn for it (Emitters::triangle_draw) and that light's emitted
  // radiance (0 where it emits nothing) and sidedness. Returns its lane. At most kLanes.
  int add(const LambertianSurface& surface, const Vec3& p, const Vec3& p_error, TriangleId leaves, const Rgb& beta,
          const Emitters::TriangleDraw& light, const Rgb& emission, bool double_sided);
  TriangleId leaves(int lane) const { return leaves_[lane]; }

 private:
  TriangleId leaves_[kLanes];
};

// The shadow ray to trace and what it adds when unoccluded (beta included); cast false: none.
struct LaneLightResult {
  Ray ray;
  Rgb contribution;
  bool cast = false;
};

// For each lane of the batch, what PathIntegrator::direct_light gives, bit for bit: the light
// sample's point, error bound and density (Emitters::sample_light: by solid angle near the light
// where that pays, else by area), the emitted radiance, the lobe's value and density
// (Bsdf::evaluate), the shadow ray (spawn_ray_between) and the power-heuristic weight. In AVX2
// where the CPU has it and `avx2` allows it, else in SSE pairs (the same bits).
void lane_direct_light(const LaneLightBatch& batch, LaneLightResult* out, bool avx2 = true);

}  // namespace prism
