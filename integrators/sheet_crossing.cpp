#include "integrators/sheet_crossing.h"

#include <algorithm>
#include <cmath>

#include "core/spawn.h"
#include "materials/material_eval.h"

namespace prism {
namespace {

// What the sheet at `hit` lets through along unit direction dir.
Rgb through_sheet(const SceneDesc& desc, const SurfaceHit& hit, const Vec3& dir, float medium_ior) {
  return straight_through(desc, hit, -dir, desc.material(hit.material).ior / medium_ior);
}

}  // namespace

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
    tr *= through_sheet(desc, hit, dir, medium_ior);
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

static_assert(Scene::SheetsCrossed::kKept >= kMaxSheetCrossings, "the query keeps every crossing a walk would take");

void shadow_transmittance(const Scene& scene, const Ray* rays, const float* medium_iors, int n, Rgb* through,
                          RayCounters& counters) {
  const bool sheets = scene.features().thin_sheets;
  if (sheets && !scene.sees_every_sheet()) {  // the query cannot see past a sheet sphere: walk every ray
    for (int k = 0; k < n; ++k) through[k] = transmittance_through_sheets(scene, rays[k], medium_iors[k], counters);
    return;
  }
  constexpr int kPacket = Scene::kPacketSize;
  bool blocked[kPacket];
  Scene::SheetsCrossed crossed[kPacket];
  for (int first = 0; first < n; first += kPacket) {
    const int m = std::min(n - first, kPacket);
    if (sheets)
      scene.occluded_past_sheets(rays + first, m, blocked, crossed);
    else
      scene.occluded_packet(rays + first, m, blocked);
    for (int j = 0; j < m; ++j) {
      const int k = first + j;
      const Scene::SheetsCrossed& c = crossed[j];
      if (!sheets || c.count == 0) {
        through[k] = Rgb(blocked[j] ? 0.0f : 1.0f);
      } else if (c.count > kMaxSheetCrossings) {
        through[k] = Rgb(0.0f);  // as the walk stops such a ray
      } else {
        // The crossings' factors in the order a walk would meet them, so that it gives the same bits.
        Scene::SheetsCrossed::Crossing met[Scene::SheetsCrossed::kKept];
        std::copy(c.met, c.met + c.count, met);
        std::sort(met, met + c.count, [](const auto& a, const auto& b) { return a.t < b.t; });
        const Vec3 dir = normalize(rays[k].dir);
        Rgb tr(1.0f);
        for (int i = 0; i < c.count; ++i) {
          SurfaceHit hit;
          scene.sheet_hit(rays[k], met[i], hit);
          tr *= through_sheet(scene.desc(), hit, dir, medium_iors[k]);
        }
        through[k] = tr;
      }
    }
  }
}

}  // namespace prism
