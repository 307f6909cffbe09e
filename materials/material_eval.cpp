#include "materials/material_eval.h"

#include <algorithm>

#include "materials/texture_lookup.h"

namespace prism {

Rgb base_color(const SceneDesc& scene, const MaterialDesc& m, Vec2 uv) {
  Rgb c = m.base_color;
  if (m.base_color_texture.present()) c *= lookup_texture(scene, m.base_color_texture, uv).rgb;
  return c;
}

SurfaceParams surface_params(const SceneDesc& scene, const MaterialDesc& m, Vec2 uv) {
  SurfaceParams p;
  p.base_color = base_color(scene, m, uv);
  p.metallic = m.metallic;
  p.roughness = m.roughness;
  if (m.metallic_roughness_texture.present()) {
    const Rgb mr = lookup_texture(scene, m.metallic_roughness_texture, uv).rgb;
    p.roughness *= mr.y;  // glTF 2.0 §3.9.2: green is roughness, blue is metalness
    p.metallic *= mr.z;
  }
  p.metallic = std::clamp(p.metallic, 0.0f, 1.0f);
  p.roughness = std::clamp(p.roughness, 0.0f, 1.0f);
  p.transmission = m.transmission;
  if (m.transmission_texture.present()) p.transmission *= lookup_texture(scene, m.transmission_texture, uv).rgb.x;
  p.transmission = std::clamp(p.transmission, 0.0f, 1.0f);
  p.ior = m.ior;
  p.thin_walled = !m.has_volume();
  return p;
}

Rgb emitted_radiance(const SceneDesc& scene, int material, Vec2 uv, const Vec3& ng, const Vec3& w) {
  const MaterialDesc& m = scene.material(material);
  if (!m.is_emissive()) return {};
  if (!m.double_sided && dot(ng, w) <= 0) return {};
  Rgb e = m.emissive * m.emissive_strength;
  if (m.emissive_texture.present()) e *= lookup_texture(scene, m.emissive_texture, uv).rgb;
  return e;
}

Bsdf make_bsdf(const SceneDesc& scene, const SurfaceHit& hit, const Vec3& wo, float eta) {
  return Bsdf(surface_params(scene, scene.material(hit.material), hit.uv), hit.ns, hit.ng, wo, eta);
}

}  // namespace prism
