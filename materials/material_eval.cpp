#include "materials/material_eval.h"

#include "materials/texture_lookup.h"

namespace prism {

Rgb base_color(const SceneDesc& scene, const MaterialDesc& m, Vec2 uv) {
  Rgb c = m.base_color;
  if (m.base_color_texture.present()) c *= lookup_texture(scene, m.base_color_texture, uv).rgb;
  return c;
}

Rgb emitted_radiance(const SceneDesc& scene, int material, Vec2 uv, const Vec3& ng, const Vec3& w) {
  const MaterialDesc& m = scene.material(material);
  if (!m.is_emissive()) return {};
  if (!m.double_sided && dot(ng, w) <= 0) return {};
  Rgb e = m.emissive * m.emissive_strength;
  if (m.emissive_texture.present()) e *= lookup_texture(scene, m.emissive_texture, uv).rgb;
  return e;
}

Bsdf make_bsdf(const SceneDesc& scene, const SurfaceHit& hit, const Vec3& wo) {
  return Bsdf(hit.ns, hit.ng, wo, base_color(scene, scene.material(hit.material), hit.uv));
}

}  // namespace prism
