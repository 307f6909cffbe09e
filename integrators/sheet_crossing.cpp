#include "integrators/sheet_crossing.h"

#include <cmath>

#include "core/spawn.h"
#include "materials/material_eval.h"

namespace prism {

Rgb transmittance_through_sheets(const Scene& scene, Ray ray, float medium_ior, RayCounters& counters) {
  const SceneDesc& desc = scene.desc();
  const bool unbounded = std::isinf(ray.t_max);
  const Vec3 end = unbounded ? Vec3(0.0f) : ray.origin + ray.dir * ray.t_max;  // where the segment stops
  const Vec3 dir = normalize(ray.dir);
  Rgb tr(1.0f);
  for (int crossed = 0; crossed <= kMaxSheetCrossings; ++crossed) {
    SurfaceHit hit;
    if (crossed > 0) ++counters.shadow;
    if (!scene.intersect(ray, hit)) return tr;
    const MaterialDesc& m = desc.material(hit.material);
    if (!m.is_thin_sheet() || crossed == kMaxSheetCrossings) return {};
    tr *= make_bsdf(desc, hit, -dir, m.ior / medium_ior).straight_through();
    if (is_black(tr)) return {};
    if (unbounded) {
      ray = spawn_ray(hit, dir);
      continue;
    }
    const Vec3 origin = offset_ray_origin(hit.p, hit.p_error, hit.ng, dir);
    if (!(dot(end - origin, dir) > 0)) return tr;  // the sheet lies at the segment's very end
    ray = Ray{origin, end - origin, 0.0f, 1.0f, hit.triangle};
  }
  return {};
}

}  // namespace prism
