// Material evaluation: turns a glTF material and a hit's uv into shading parameters, a BSDF and
// emitted radiance.
#pragma once

#include <optional>

#include "core/scene_desc.h"
#include "core/surface_hit.h"
#include "materials/bsdf.h"
#include "materials/surface_params.h"

namespace prism {

// Base colour (factor x sRGB-decoded texture), linear. uv_width > 0: the lookup's footprint in uv
// units, for MIP-mapped textures (lookup_texture).
Rgb base_color(const SceneDesc& scene, const MaterialDesc& m, Vec2 uv, float uv_width = 0);

// Coverage: base colour alpha factor x texture alpha (glTF alphaMode MASK and BLEND); fits
// Scene's AlphaFunction.
float material_alpha(const SceneDesc& scene, int material, Vec2 uv);

// Every glTF factor multiplied by its texture at uv, over a footprint uv_width wide (as base_color).
SurfaceParams surface_params(const SceneDesc& scene, const MaterialDesc& m, Vec2 uv, float uv_width = 0);

// Bsdf::lambertian_only at every point of `m`, for the interface's eta, where no texture scales
// the factors it depends on (metallic, transmission, specular); nullopt where one does.
// Inline: asked at every vertex the lanes may take (out of line it cost 1.2% of the box).
inline std::optional<bool> lambertian_everywhere(const MaterialDesc& m, float eta) {
  if (m.metallic_roughness_texture.present() || m.transmission_texture.present() || m.specular_texture.present())
    return std::nullopt;
  return Bsdf::lambertian_only(m.metallic, m.transmission, m.specular, eta);
}

// Radiance emitted by material `material` at uv toward w, for a surface whose front-face
// normal is ng: emissive factor x texture x strength, from the front face only unless the
// material is double-sided. The texture is read at level 0 alone, as light sampling reads it, so
// that both strategies of multiple importance sampling see the same emission.
Rgb emitted_radiance(const SceneDesc& scene, int material, Vec2 uv, const Vec3& ng, const Vec3& w);

// The shading normal at a hit: the interpolated normal, bent by the material's normal map in the
// hit's tangent frame (glTF 2.0 §3.9.3: n = normalize(T x + B y + N z), x and y scaled).
Vec3 shading_normal(const SceneDesc& scene, const MaterialDesc& m, const SurfaceHit& hit);

// Starts fetching into the cache the texels every texture of `m` will read at uv over a footprint
// uv_width wide (see prefetch_texture).
void prefetch_textures(const SceneDesc& scene, const MaterialDesc& m, Vec2 uv, float uv_width = 0);

// The BSDF at a hit, for light leaving toward wo; eta = n_back / n_front at the surface.
Bsdf make_bsdf(const SceneDesc& scene, const SurfaceHit& hit, const Vec3& wo, float eta);
// What passes straight through the surface at a hit along -wo (Bsdf::straight_through).
Rgb straight_through(const SceneDesc& scene, const SurfaceHit& hit, const Vec3& wo, float eta);

}  // namespace prism
