// Thin sheets that light crosses straight on: shadow rays through window panes and bubbles.
#pragma once

#include "core/ray.h"
#include "core/ray_counters.h"
#include "core/scene.h"
#include "core/vec3.h"

namespace prism {

// A smooth thin-walled sheet (glTF transmission without KHR_materials_volume) passes light along
// a straight line, so a shadow ray may cross it and next-event estimation can light a room through
// its window: the light a path would otherwise find only by drawing that very direction (never,
// for a sun or a point light). The path tracer keeps its MIS consistent with this by not counting
// a straight crossing as a scattering event (integrators/path_integrator.cpp).
inline constexpr int kMaxSheetCrossings = 16;  // per straight segment, for shadow rays and paths alike

// What shadow ray `ray` lets through: it is traced hit by hit (closest hits, so scenes without thin
// sheets are better served by an occlusion query), each smooth thin sheet multiplying by its
// straight transmission for that direction (Bsdf::straight_through), and anything else, or more
// than kMaxSheetCrossings sheets, stopping it (black). medium_ior is the index of the medium the
// ray travels in. Each segment after the first counts as one more shadow ray.
Rgb transmittance_through_sheets(const Scene& scene, Ray ray, float medium_ior, RayCounters& counters);

// What each of n shadow rays lets through, in any scene: one occlusion query per packet of eight
// answers 1 or 0, or, past thin sheets (Scene::occluded_past_sheets), names the sheets the ray
// crosses, whose straight transmittances are then multiplied: what transmittance_through_sheets
// gives, without its closest hits. The query decides every surface with alpha once, by its own
// ray. In a scene with a sheet sphere, which the query cannot see past, every ray is walked.
// medium_iors[k] is the index of the medium rays[k] travels in.
void shadow_transmittance(const Scene& scene, const Ray* rays, const float* medium_iors, int n, Rgb* through,
                          RayCounters& counters);

}  // namespace prism
