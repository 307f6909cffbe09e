#include "integrators/sheet_crossing.h"

#include <algorithm>
#include <cmath>

#include "core/spawn.h"
#include "materials/material_eval.h"

namespace prism {

Rgb transmittance_through_sheets(const Scene& scene, Ray ray, float medium_ior, RayCounters& counters,
                                 bool clear_but_sheets) {
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
    if (crossed == kMaxSheetCrossings || !(m.is_thin_sheet() || clear_but_sheets)) return {};
    if (m.is_thin_sheet()) {
      tr *= make_bsdf(desc, hit, -dir, m.ior / medium_ior).straight_through();
      if (is_black(tr)) return {};
    }
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

void shadow_transmittance(const Scene& scene, const Ray* rays, const float* medium_iors, const bool* expects_sheet,
                          int n, Rgb* through, RayCounters& counters) {
  constexpr int kPacket = Scene::kPacketSize;
  bool blocked[kPacket], crossed[kPacket];
  if (!scene.features().thin_sheets) {
    for (int first = 0; first < n; first += kPacket) {
      const int m = std::min(n - first, kPacket);
      scene.occluded_packet(rays + first, m, blocked);
      for (int k = 0; k < m; ++k) through[first + k] = Rgb(blocked[k] ? 0.0f : 1.0f);
    }
    return;
  }
  // The occlusion query cannot see past a sheet sphere: then every ray is walked.
  const bool query = scene.sees_every_sheet();
  Ray asked[kPacket];
  int asked_index[kPacket];
  for (int first = 0; first < n; first += kPacket) {
    const int m = std::min(n - first, kPacket);
    int q = 0;
    for (int k = first; k < first + m; ++k) {
      if (query && !(expects_sheet && expects_sheet[k])) {
        asked[q] = rays[k];
        asked_index[q++] = k;
      } else {
        through[k] = transmittance_through_sheets(scene, rays[k], medium_iors[k], counters);
      }
    }
    if (q == 0) continue;
    scene.occluded_past_sheets(asked, q, blocked, crossed);
    for (int j = 0; j < q; ++j) {
      const int k = asked_index[j];
      if (!crossed[j]) {
        through[k] = Rgb(blocked[j] ? 0.0f : 1.0f);
        continue;
      }
      ++counters.shadow;
      through[k] = transmittance_through_sheets(scene, rays[k], medium_iors[k], counters, /*clear_but_sheets=*/true);
    }
  }
}

}  // namespace prism
