#include "integrators/path_integrator.h"

#include <algorithm>
#include <cmath>

#include "core/spawn.h"
#include "integrators/first_hit_aovs.h"
#include "integrators/medium_stack.h"
#include "materials/material_eval.h"
#include "materials/medium.h"

namespace prism {

// Light arriving at `hit` from one sampled light, through the BSDF, unoccluded, attenuated by the
// medium on the light's side of the surface, weighted by MIS against BSDF sampling (area lights).
Rgb PathIntegrator::direct_light(const Scene& scene, const SurfaceHit& hit, const Bsdf& bsdf, const MediumStack& media,
                                 const MaterialDesc& material, bool from_front, float u_pick, Vec2 u_point,
                                 RayCounters& counters) const {
  const SceneDesc& desc = scene.desc();
  const EmitterSample ls = scene.emitters().sample(hit.p, u_pick, u_point);
  if (!(ls.pdf > 0)) return {};
  Vec3 wi;
  float dist;
  Rgb incident;
  if (ls.delta || ls.infinite) {
    wi = ls.wi;
    dist = ls.distance;
    incident = ls.incident;
  } else {
    const Vec3 to_light = ls.p - hit.p;
    dist = length(to_light);
    wi = to_light / dist;
    incident = emitted_radiance(desc, ls.material, ls.uv, ls.n, -wi);
  }
  const Rgb f = bsdf.eval(wi);
  if (is_black(incident) || is_black(f)) return {};
  ++counters.shadow;
  const Ray shadow = ls.delta || ls.infinite ? spawn_ray_toward(hit, wi, dist)
                                             : spawn_ray_between(hit, ls.p, ls.p_error, ls.n);
  if (scene.occluded(shadow)) return {};
  // The shadow ray travels in the medium on wi's side of the surface.
  Rgb sigma = media.sigma_a();
  if ((dot(wi, hit.ng) > 0) != from_front && material.has_volume()) {
    MediumStack beyond = media;
    beyond.cross(material, hit.material, from_front);
    sigma = beyond.sigma_a();
  }
  const Rgb tr = beer_lambert(sigma, dist);
  const float weight = ls.delta ? 1.0f : power_heuristic(ls.pdf, bsdf.pdf(wi));
  return f * incident * tr * (weight / ls.pdf);
}

// Each bounce draws, in order: emitter pick (1D), point on the emitter (2D), BSDF lobe (1D) and
// direction (2D), then the Russian-roulette decision (1D) once it applies.
RadianceSample PathIntegrator::li(const Scene& scene, const Ray& camera_ray, Sampler& sampler,
                                  RayCounters& counters, AovSample* aov) const {
  const SceneDesc& desc = scene.desc();
  const Emitters& emitters = scene.emitters();
  RadianceSample out;
  // Light seen directly, after one scattering event, and after more.
  Rgb emitted(0.0f), direct(0.0f), indirect(0.0f), beta(1.0f);
  float eta_scale = 1.0f;  // undoes the 1/eta^2 radiance scaling in Russian roulette decisions
  Ray ray = camera_ray;
  ++counters.camera;
  float prev_bsdf_pdf = 0;  // solid-angle pdf of the direction that led to the current hit
  bool prev_delta = true;   // the camera ray counts as a delta event: no MIS for what it sees
  Vec3 prev_p;
  MediumStack media;
  int diffuse_depth = 0;
  bool last_vertex = false;  // the diffuse-bounce limit is reached: only emission (MIS) is left

  for (int depth = 0;; ++depth) {
    SurfaceHit hit;
    if (!scene.intersect(ray, hit, depth == 0)) {
      // Escaped to the sky: the environment, MIS-weighted against light sampling after a
      // non-delta bounce; inside an absorbing medium the infinite segment absorbs completely.
      const EnvironmentLight& env = emitters.environment();
      if (env.present()) {
        const Vec3 w = normalize(ray.dir);
        const float weight = prev_delta ? 1.0f : power_heuristic(prev_bsdf_pdf, emitters.environment_pdf(w));
        (depth == 0 ? emitted : depth == 1 ? direct : indirect) +=
            beta * env.radiance(w) * beer_lambert(media.sigma_a(), kInfinity) * weight;
      }
      break;
    }
    if (depth == 0) {
      out.alpha = 1.0f;
      if (aov) report_first_hit(desc, hit, *aov);
    }
    // Beer-Lambert along the segment, measured between the surface points themselves: the spawned
    // origin sits off its surface by the hit's error bound, which far from the world origin is a
    // visible part of a thin slab's thickness.
    beta *= beer_lambert(media.sigma_a(), depth == 0 ? hit.t * length(ray.dir) : length(hit.p - prev_p));
    const Vec3 wo = -normalize(ray.dir);

    // Emission reached by the previous bounce: weighted against next-event estimation by the
    // power heuristic (Veach 1997, ch. 9); unweighted after a delta event.
    if (hit.emitter >= 0) {
      const Rgb Le = emitted_radiance(desc, hit.material, hit.uv, hit.ng, wo);
      if (!is_black(Le)) {
        float w = 1.0f;
        if (!prev_delta) w = power_heuristic(prev_bsdf_pdf, emitters.pdf(hit.emitter, prev_p, hit.p, hit.ng));
        (depth == 0 ? emitted : depth == 1 ? direct : indirect) += beta * Le * w;
      }
    }
    if (depth >= max_depth_ || last_vertex) break;

    const MaterialDesc& material = desc.material(hit.material);
    const bool from_front = dot(wo, hit.ng) > 0;
    const Bsdf bsdf = make_bsdf(desc, hit, wo, media.interface_eta(material, hit.material, from_front));

    // Next-event estimation: one light chosen by power; a point on it for area lights.
    if (!emitters.empty() && !bsdf.is_delta()) {
      const float u_pick = sampler.next_1d();
      const Vec2 u_point = sampler.next_2d();
      (depth == 0 ? direct : indirect) += beta * direct_light(scene, hit, bsdf, media, material, from_front, u_pick, u_point, counters);
    }

    const float u_lobe = sampler.next_1d();
    const auto bs = bsdf.sample(u_lobe, sampler.next_2d());
    if (!bs) break;
    beta *= bs->f_cos / bs->pdf;
    prev_bsdf_pdf = bs->pdf;
    prev_delta = bs->delta;
    // Past the diffuse limit the sampled ray still finds the emitter it hits (its MIS half of
    // direct lighting), then the path ends.
    if (!bs->delta && max_diffuse_depth_ >= 0 && ++diffuse_depth > max_diffuse_depth_) last_vertex = true;
    prev_p = hit.p;
    if (bs->transmission) {
      media.cross(material, hit.material, from_front);
      if (material.has_volume()) eta_scale *= bs->eta * bs->eta;
    }
    ray = spawn_ray(hit, bs->wi);

    // Russian roulette on the throughput without the radiance scaling of refraction, so paths
    // inside glass are not killed for having crossed into it; survivors are reweighted.
    if (depth + 1 >= rr_start_depth_) {
      const float q = std::max(0.0f, 1.0f - max_component(beta) * eta_scale);
      if (sampler.next_1d() < q) break;
      beta /= 1.0f - q;
    }
    ++counters.extension;
  }
  if (clamp_indirect_ > 0) {
    const float m = max_component(indirect);
    if (m > clamp_indirect_) indirect *= clamp_indirect_ / m;
  }
  out.radiance = emitted + direct + indirect;
  if (aov) {
    aov->emission = emitted;
    aov->direct = direct;
    aov->indirect = indirect;
  }
  return out;
}

}  // namespace prism
