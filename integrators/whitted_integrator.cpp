#include "integrators/whitted_integrator.h"

#include <cmath>

#include "core/punctual_light.h"
#include "core/spawn.h"
#include "integrators/first_hit_aovs.h"
#include "integrators/sheet_crossing.h"
#include "materials/dielectric_bxdf.h"
#include "materials/fresnel.h"
#include "materials/material_eval.h"
#include "materials/medium.h"

namespace prism {

RadianceSample WhittedIntegrator::li(const Scene& scene, const Ray& camera_ray, Sampler&, RayCounters& counters,
                                     AovSample* aov) const {
  ++counters.camera;
  RadianceSample out;
  out.radiance = trace(scene, camera_ray, nullptr, 0, MediumStack(), counters, &out.alpha, aov);
  return out;
}

Rgb WhittedIntegrator::trace(const Scene& scene, const Ray& ray, const Vec3* from, int depth,
                             const MediumStack& media, RayCounters& counters, float* alpha, AovSample* aov) const {
  SurfaceHit hit;
  if (!scene.intersect(ray, hit, depth == 0)) {
    const EnvironmentLight& env = scene.emitters().environment();
    const Rgb sky = env.present() ? env.radiance(normalize(ray.dir)) * beer_lambert(media.sigma_a(), kInfinity) : Rgb{};
    if (aov) aov->emission = sky;
    return sky;
  }
  hit.cone_width = ray.cone_width_at(hit.t);
  if (alpha) *alpha = 1.0f;
  if (aov) report_first_hit(scene.desc(), hit, *aov);
  const SceneDesc& desc = scene.desc();
  const Vec3 wo = -normalize(ray.dir);
  // Measured between the surface points, not from the offset origin (as in the path tracer).
  const Rgb absorbed = beer_lambert(media.sigma_a(), from ? length(hit.p - *from) : hit.t * length(ray.dir));
  const Rgb Le = emitted_radiance(desc, hit.material, hit.uv, hit.ng, wo);
  Rgb direct(0.0f), indirect(0.0f);  // from the lights, and through mirrors and glass
  const auto result = [&] {
    if (aov) {
      aov->emission = Le * absorbed;
      aov->direct = direct * absorbed;
      aov->indirect = indirect * absorbed;
    }
    return (Le + direct + indirect) * absorbed;
  };
  if (depth >= max_depth_) return result();

  const MaterialDesc& material = desc.material(hit.material);
  const SurfaceParams p = surface_params(desc, material, hit.uv, hit.uv_width());
  const bool from_front = dot(wo, hit.ng) > 0;
  const bool volume = p.transmission > 0 && !p.thin_walled;
  const float eta = media.interface_eta(material, hit.material, from_front);
  // The (normal-mapped) shading normal on the front face; opaque and thin surfaces are
  // two-sided, so their normals then face wo.
  const Vec3 bent = shading_normal(desc, material, hit);
  const Vec3 n_front = dot(bent, hit.ng) < 0 ? -bent : bent;
  Vec3 ng = hit.ng, ns = n_front;
  if (!from_front && !volume) {
    ng = -ng;
    ns = -ns;
  }
  const Vec3 n_wo = dot(wo, ns) < 0 ? -ns : ns;  // reflection happens on wo's side, inside glass too
  const float cos_o = dot(wo, n_wo);
  const float m = p.metallic, t = p.transmission;

  // Fresnel-weighted shares of the mirror direction and the transmitted one, from the same
  // smooth interfaces the path tracer samples (a thin sheet reflects from both faces).
  const DielectricBxdf::Mode mode = volume ? DielectricBxdf::Mode::Volume
                                           : (t > 0 ? DielectricBxdf::Mode::ThinWalled : DielectricBxdf::Mode::ReflectionOnly);
  const float R = DielectricBxdf(eta, 0.0f, Rgb(1.0f), mode).reflectance(volume ? dot(wo, n_front) : std::abs(cos_o));
  const Rgb reflect_weight = fresnel_schlick(p.base_color, cos_o) * m + Rgb((1 - m) * R);
  const Rgb transmit_weight = p.base_color * ((1 - m) * t * (1 - R));
  const float diffuse_weight = (1 - m) * (1 - t) * (1 - R);

  // Diffuse: direct light from punctual lights, with shadow rays.
  if (diffuse_weight > 0 && dot(wo, ns) > 0) {
    const Rgb f = p.base_color * (diffuse_weight * kInvPi);
    for (const PunctualLightDesc& light : desc.lights) {
      const PunctualIncidence in = punctual_incidence(light, hit.p);
      const float cos_i = dot(in.wi, ns);
      if (cos_i <= 0 || dot(in.wi, ng) <= 0 || is_black(in.irradiance)) continue;
      ++counters.shadow;
      const Ray shadow = spawn_ray_toward(hit, in.wi, in.distance);
      // A window pane lets a lamp outside light the room.
      const float ior = media.ior();
      Rgb through;
      shadow_transmittance(scene, &shadow, &ior, 1, &through, counters);
      direct += f * in.irradiance * cos_i * through;
    }
  }

  // Mirror reflection (metal, the dielectric layer, and glass's reflected share).
  if (!is_black(reflect_weight) && cos_o > 0) {
    const Vec3 wr = reflect(wo, n_wo);
    if (dot(wr, ng) * dot(wo, ng) > 0) {
      ++counters.extension;
      indirect += reflect_weight * trace(scene, spawn_ray_cone(hit, wr, ray), &hit.p, depth + 1, media, counters);
    }
  }

  // Transmission: straight through a thin sheet, refracted into or out of a volume.
  if (!is_black(transmit_weight)) {
    if (!volume) {
      ++counters.extension;
      indirect += transmit_weight * trace(scene, spawn_ray_cone(hit, -wo, ray), &hit.p, depth + 1, media, counters);
    } else {
      const Vec3 n = from_front ? n_front : -n_front;  // on wo's side
      const float etap = from_front ? eta : 1.0f / eta;
      Vec3 wt;
      if (R < 1.0f && refract(wo, n, etap, wt) && dot(wt, hit.ng) * dot(wo, hit.ng) < 0) {
        MediumStack inside = media;
        inside.cross(material, hit.material, from_front);
        ++counters.extension;
        indirect += transmit_weight * (1.0f / (etap * etap)) *
                    trace(scene, spawn_ray_cone(hit, wt, ray), &hit.p, depth + 1, inside, counters);
      }
    }
  }
  return result();
}

}  // namespace prism
