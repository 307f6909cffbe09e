#include "integrators/path_integrator.h"

#include <algorithm>

#include "core/spawn.h"
#include "materials/material_eval.h"

namespace prism {

// Each bounce draws, in order: emitter pick (1D), point on the emitter (2D), BSDF direction
// (2D), then the Russian-roulette decision (1D) once it applies.
RadianceSample PathIntegrator::li(const Scene& scene, const Ray& camera_ray, Sampler& sampler,
                                  RayCounters& counters) const {
  const SceneDesc& desc = scene.desc();
  const Emitters& emitters = scene.emitters();
  RadianceSample out;
  Rgb L(0.0f), beta(1.0f);
  Ray ray = camera_ray;
  ++counters.camera;
  float prev_bsdf_pdf = 0;  // solid-angle pdf of the direction that led to the current hit
  Vec3 prev_p;

  for (int depth = 0;; ++depth) {
    SurfaceHit hit;
    if (!scene.intersect(ray, hit, depth == 0)) break;
    if (depth == 0) out.alpha = 1.0f;
    const Vec3 wo = -normalize(ray.dir);

    // Emission reached by the previous bounce: weighted against next-event estimation by the
    // power heuristic (Veach 1997, ch. 9), unweighted for the camera ray.
    if (hit.emitter >= 0) {
      const Rgb Le = emitted_radiance(desc, hit.material, hit.uv, hit.ng, wo);
      if (!is_black(Le)) {
        float w = 1.0f;
        if (depth > 0) w = power_heuristic(prev_bsdf_pdf, emitters.pdf(hit.emitter, prev_p, hit.p, hit.ng));
        L += beta * Le * w;
      }
    }
    if (depth >= max_depth_) break;

    const Bsdf bsdf = make_bsdf(desc, hit, wo);

    // Next-event estimation: one point on one emitter, chosen by power.
    if (!emitters.empty()) {
      const float u_pick = sampler.next_1d();
      const Vec2 u_point = sampler.next_2d();
      const EmitterSample ls = emitters.sample(hit.p, u_pick, u_point);
      if (ls.pdf > 0) {
        const Vec3 wi = normalize(ls.p - hit.p);
        const Rgb Le = emitted_radiance(desc, ls.material, ls.uv, ls.n, -wi);
        const Rgb f = bsdf.eval(wi);
        if (!is_black(Le) && !is_black(f)) {
          ++counters.shadow;
          const Ray shadow = spawn_ray_between(hit.p, hit.p_error, hit.ng, ls.p, ls.p_error, ls.n);
          if (!scene.occluded(shadow)) L += beta * f * Le * (power_heuristic(ls.pdf, bsdf.pdf(wi)) / ls.pdf);
        }
      }
    }

    const auto bs = bsdf.sample(sampler.next_2d());
    if (!bs) break;
    beta *= bs->f_cos / bs->pdf;
    prev_bsdf_pdf = bs->pdf;
    prev_p = hit.p;
    ray = spawn_ray(hit.p, hit.p_error, hit.ng, bs->wi);

    // Russian roulette on the throughput: survivors are reweighted, so the estimate stays unbiased.
    if (depth + 1 >= rr_start_depth_) {
      const float q = std::max(0.0f, 1.0f - max_component(beta));
      if (sampler.next_1d() < q) break;
      beta /= 1.0f - q;
    }
    ++counters.extension;
  }
  out.radiance = L;
  return out;
}

}  // namespace prism
