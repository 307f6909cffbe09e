// LaneLightBatch, lane_direct_light: next-event estimation at Lambertian vertices toward area-drawn points, in lanes.
#pragma once

#include "core/emitters.h"
#include "core/ray.h"
#include "core/vec3.h"
#include "integrators/lane_rows.h"
#include "materials/bsdf.h"

namespace prism {

// A light request's fields; rows of three hold a vector's x, y and z.
struct LaneLightFields {
  enum Row {
    kP = 0, kPError = 3, kNg = 6, kBsdfN = 9, kBsdfNg = 12, kF = 15, kBeta = 18, kC0 = 21, kC1 = 24, kC2 = 27,
    kLightN = 30, kEmission = 33,  // the rows of three above, one each below
    kWoDotNg = 36, kWoZ, kB0, kB1, kB2, kSlack, kPdfArea, kPmf, kDoubleSided, kRows
  };
};

// Up to kLanes vertices' light requests. Outside every volume only: no medium absorbs.
class LaneLightBatch : public LaneLightFields, public LaneRows<LaneLightFields::kRows> {
 public:
  // A vertex: its hit's point, the point's error bound, its geometric normal and triangle, its
  // Lambertian lobe and the path's throughput, with the light point drawn for it
  // (Emitters::area_draw) and that light's emitted radiance (0 where it emits nothing) and
  // sidedness. Returns its lane. At most kLanes.
  int add(const Vec3& p, const Vec3& p_error, const Vec3& ng, TriangleId leaves, const Bsdf::LambertianLobe& lobe,
          const Rgb& beta, const Emitters::AreaDraw& light, const Rgb& emission, bool double_sided);
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
// sample's point, error bound and density (Emitters::sample_light by area), the emitted radiance,
// the lobe's value and density (Bsdf::evaluate), the shadow ray (spawn_ray_between) and the
// power-heuristic weight. In AVX2 where the CPU has it and `avx2` allows it, else in SSE pairs
// (the same bits).
void lane_direct_light(const LaneLightBatch& batch, LaneLightResult* out, bool avx2 = true);

}  // namespace prism
