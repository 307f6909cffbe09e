// LaneLightBatch, lane_direct_light: next-event estimation at Lambertian vertices toward points drawn by area, in SIMD lanes.
#pragma once

#include "core/emitters.h"
#include "core/ray.h"
#include "core/vec3.h"
#include "materials/bsdf.h"

namespace prism {

// Up to kLanes vertices' requests, each field a row of lanes, written lane by lane as the vertices
// shade and read eight lanes at a time. Outside every volume only: no medium absorbs.
class LaneLightBatch {
 public:
  static constexpr int kLanes = 32;

  int size() const { return size_; }
  void clear() { size_ = 0; }
  // A vertex: its hit's point, the point's error bound, its geometric normal and triangle, its
  // Lambertian lobe and the path's throughput, with the light point drawn for it
  // (Emitters::area_draw) and that light's emitted radiance (0 where it emits nothing) and
  // sidedness. Returns its lane. At most kLanes.
  int add(const Vec3& p, const Vec3& p_error, const Vec3& ng, TriangleId leaves, const Bsdf::LambertianLobe& lobe,
          const Rgb& beta, const Emitters::AreaDraw& light, const Rgb& emission, bool double_sided);

  // Rows of three hold a vector's x, y and z.
  enum Row {
    kP = 0, kPError = 3, kNg = 6, kBsdfN = 9, kBsdfNg = 12, kF = 15, kBeta = 18, kC0 = 21, kC1 = 24, kC2 = 27,
    kLightN = 30, kEmission = 33,  // the rows of three above, one each below
    kWoDotNg = 36, kWoZ, kB0, kB1, kB2, kSlack, kPdfArea, kPmf, kDoubleSided, kRows
  };
  const float* row(int r) const { return rows_[r]; }
  TriangleId leaves(int lane) const { return leaves_[lane]; }

 private:
  void set(int r, int lane, const Vec3& v) {
    rows_[r][lane] = v.x;
    rows_[r + 1][lane] = v.y;
    rows_[r + 2][lane] = v.z;
  }
  // Zeros at first: lanes past size() hold finite values, whose results are never read.
  alignas(32) float rows_[kRows][kLanes] = {};
  TriangleId leaves_[kLanes];
  int size_ = 0;
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
