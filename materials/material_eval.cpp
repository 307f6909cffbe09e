#include "materials/material_eval.h"

#include <algorithm>

#include "materials/texture_lookup.h"

namespace prism {

Rgb base_color(const SceneDesc& scene, const MaterialDesc& m, Vec2 uv, float uv_width) {
  Rgb c = m.base_color;
  if (m.base_color_texture.present()) c *= lookup_texture(scene, m.base_color_texture, uv, uv_width).rgb;
  return c;
}

float material_alpha(const SceneDesc& scene, int material, Vec2 uv) {
  const MaterialDesc& m = scene.material(material);
  float a = m.base_alpha;
  if (m.base_color_texture.present()) a *= lookup_texture(scene, m.base_color_texture, uv).a;
  return a;
}

SurfaceParams surface_params(const SceneDesc& scene, const MaterialDesc& m, Vec2 uv, float uv_width) {
  SurfaceParams p;
  p.base_color = base_color(scene, m, uv, uv_width);
  p.metallic = m.metallic;
  p.roughness = m.roughness;
  if (m.metallic_roughness_texture.present()) {
    const Rgb mr = lookup_texture(scene, m.metallic_roughness_texture, uv, uv_width).rgb;
    p.roughness *= mr.y;  // glTF 2.0 §3.9.2: green is roughness, blue is metalness
    p.metallic *= mr.z;
  }
  p.metallic = std::clamp(p.metallic, 0.0f, 1.0f);
  p.roughness = std::clamp(p.roughness, 0.0f, 1.0f);
  p.transmission = m.transmission;
  if (m.transmission_texture.present()) p.transmission *= lookup_texture(scene, m.transmission_texture, uv, uv_width).rgb.x;
  p.transmission = std::clamp(p.transmission, 0.0f, 1.0f);
  p.ior = m.ior;
  p.thin_walled = !m.has_volume();
  p.specular = m.specular;
  if (m.specular_texture.present()) p.specular *= lookup_texture(scene, m.specular_texture, uv, uv_width).a;
  p.specular_color = m.specular_color;
  if (m.specular_color_texture.present()) p.specular_color *= lookup_texture(scene, m.specular_color_texture, uv, uv_width).rgb;
  return p;
}

Rgb emitted_radiance(const SceneDesc& scene, int material, Vec2 uv, const Vec3& ng, const Vec3& w) {
  const MaterialDesc& m = scene.material(material);
  if (!m.is_emissive()) return {};
  if (!m.double_sided && dot(ng, w) <= 0) return {};
  Rgb e = m.emission_factor();
  if (m.emissive_texture.present()) e *= lookup_texture(scene, m.emissive_texture, uv).rgb;
  return e;
}

Vec3 shading_normal(const SceneDesc& scene, const MaterialDesc& m, const SurfaceHit& hit) {
  if (!m.normal_texture.present() || length_squared(hit.tangent) == 0) return hit.ns;
  const Vec3 t = hit.tangent - hit.ns * dot(hit.ns, hit.tangent);
  if (!(length_squared(t) > 1e-12f)) return hit.ns;
  const Vec3 tangent = normalize(t);
  const Vec3 bitangent = cross(hit.ns, tangent) * hit.tangent_sign;
  const Rgb c = lookup_texture(scene, m.normal_texture, hit.uv, hit.uv_width()).rgb;
  const Vec3 local((2.0f * c.x - 1.0f) * m.normal_scale, (2.0f * c.y - 1.0f) * m.normal_scale, 2.0f * c.z - 1.0f);
  const Vec3 n = tangent * local.x + bitangent * local.y + hit.ns * local.z;
  const float len = length(n);
  return len > 0 && std::isfinite(len) ? n / len : hit.ns;
}

void prefetch_textures(const SceneDesc& scene, const MaterialDesc& m, Vec2 uv, float uv_width) {
  for (const TextureRef* ref : m.texture_slots())
    if (ref->present()) prefetch_texture(scene, *ref, uv, ref == &m.emissive_texture ? 0.0f : uv_width);
}

Bsdf make_bsdf(const SceneDesc& scene, const SurfaceHit& hit, const Vec3& wo, float eta) {
  const MaterialDesc& m = scene.material(hit.material);
  return Bsdf(surface_params(scene, m, hit.uv, hit.uv_width()), shading_normal(scene, m, hit), hit.ng, wo, eta);
}

Rgb straight_through(const SceneDesc& scene, const SurfaceHit& hit, const Vec3& wo, float eta) {
  const MaterialDesc& m = scene.material(hit.material);
  return Bsdf::straight_through(surface_params(scene, m, hit.uv, hit.uv_width()), shading_normal(scene, m, hit),
                                hit.ng, wo, eta);
}

}  // namespace prism
