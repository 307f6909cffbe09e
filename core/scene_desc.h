// SceneDesc: the plain-data scene that loaders produce and Scene::build consumes (no files, no Embree).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/image_desc.h"
#include "core/transform.h"
#include "core/vec3.h"

namespace prism {

enum class WrapMode { Repeat, ClampToEdge, MirroredRepeat };

struct TextureDesc {
  int image = -1;
  WrapMode wrap_s = WrapMode::Repeat, wrap_t = WrapMode::Repeat;
  bool nearest = false;  // magnification filter NEAREST, else bilinear
};

struct TextureRef {
  int texture = -1;  // index into SceneDesc::textures; -1 = none
  int texcoord = 0;  // which TEXCOORD_n set (prism reads set 0)
  // KHR_texture_transform as a 2x3 affine map of uv, row-major: identity when absent.
  std::array<float, 6> transform{1, 0, 0, 0, 1, 0};
  bool present() const { return texture >= 0; }
  Vec2 apply(Vec2 uv) const {
    return {transform[0] * uv.x + transform[1] * uv.y + transform[2], transform[3] * uv.x + transform[4] * uv.y + transform[5]};
  }
};

// The glTF 2.0 material model as data. Colours are linear; base_color and emissive textures
// are decoded from sRGB when loaded.
struct MaterialDesc {
  std::string name;
  Rgb base_color{1, 1, 1};
  float base_alpha = 1.0f;
  TextureRef base_color_texture;
  float metallic = 1.0f;
  float roughness = 1.0f;
  TextureRef metallic_roughness_texture;  // linear; B = metallic, G = roughness
  float transmission = 0.0f;              // KHR_materials_transmission
  TextureRef transmission_texture;        // linear; R = transmission
  float ior = 1.5f;                       // KHR_materials_ior
  float specular = 1.0f;                  // KHR_materials_specular: strength of the dielectric layer
  TextureRef specular_texture;            // linear; A = specular
  Rgb specular_color{1, 1, 1};            // tint of the layer's F0
  TextureRef specular_color_texture;      // sRGB
  // KHR_materials_volume with thicknessFactor > 0: the mesh bounds a volume that refracts and
  // absorbs; otherwise transmission is thin-walled (glTF KHR_materials_volume, "thin-walled").
  bool volume = false;
  Rgb attenuation_color{1, 1, 1};
  float attenuation_distance = std::numeric_limits<float>::infinity();
  Rgb emissive{0, 0, 0};
  float emissive_strength = 1.0f;  // KHR_materials_emissive_strength
  TextureRef emissive_texture;
  TextureRef normal_texture;  // linear; tangent-space normal, +X right and +Y up the image
  float normal_scale = 1.0f;
  bool double_sided = false;  // emits from both faces when true; from the front face only otherwise
  enum class AlphaMode { Opaque, Mask, Blend } alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;  // MASK: coverage below this is a hole

  bool is_emissive() const { return emissive_strength > 0 && max_component(emissive) > 0; }
  // The radiance emitted before the emissive texture: factor x strength, 0 where it emits nothing.
  Rgb emission_factor() const { return is_emissive() ? emissive * emissive_strength : Rgb(0.0f); }
  bool has_alpha() const { return alpha_mode != AlphaMode::Opaque; }
  // Every texture slot, present or not: what validation, feature detection and prefetching walk.
  std::array<const TextureRef*, 7> texture_slots() const {
    return {&base_color_texture,   &metallic_roughness_texture, &normal_texture,        &emissive_texture,
            &transmission_texture, &specular_texture,           &specular_color_texture};
  }
  bool has_textures() const {
    for (const TextureRef* ref : texture_slots())
      if (ref->present()) return true;
    return false;
  }
  bool is_transmissive() const { return transmission > 0 || transmission_texture.present(); }
  // A closed volume whose interior is a medium (refraction, absorption).
  bool has_volume() const { return volume && is_transmissive(); }
  // Transmits without bounding a volume: an infinitely thin sheet (a window pane, a bubble).
  bool is_thin_sheet() const { return is_transmissive() && !volume; }
};

// One triangle list with one material (a glTF primitive). Normals and uvs are per vertex and
// either empty or as long as positions; empty normals mean flat shading.
struct PrimitiveDesc {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<Vec2> uvs;
  std::vector<uint32_t> indices;  // 3 per triangle, each < positions.size()
  // Per-vertex tangent frames for normal maps (glTF TANGENT: xyz and the handedness w, so that
  // bitangent = w cross(normal, tangent) points up the texture image); empty when absent.
  std::vector<Vec3> tangents;
  std::vector<float> tangent_signs;
  int material = -1;              // -1 = the default material

  size_t triangle_count() const { return indices.size() / 3; }
};

// A mesh in object space: the unit of instancing.
struct MeshDesc {
  std::string name;
  std::vector<PrimitiveDesc> primitives;
};

// A placement of a mesh in the world.
struct InstanceDesc {
  std::string name;
  int mesh = -1;
  Transform object_to_world;
};

// Corner k (0, 1 or 2) of triangle t of `prim`, in the world where `inst` places it.
inline Vec3 world_corner(const InstanceDesc& inst, const PrimitiveDesc& prim, size_t t, int k) {
  return inst.object_to_world.point(prim.positions[prim.indices[3 * t + size_t(k)]]);
}

// An analytic sphere in world space.
struct SphereDesc {
  std::string name;
  Vec3 center;
  float radius = 1.0f;
  int material = -1;
};

// A KHR_lights_punctual light placed in the world. Units (the one place they are converted):
// prism's radiance unit is the nit (cd/m^2), so a point or spot light's intensity in candela is
// its radiant intensity as is (irradiance I / d^2 in lux, reflected radiance rho E / pi in nits),
// and a directional light's intensity in lux is the irradiance it delivers to a surface facing
// it. `color x intensity` is stored; no 683 lm/W factor is applied anywhere.
enum class LightType { Point, Spot, Directional };

struct PunctualLightDesc {
  std::string name;
  LightType type = LightType::Point;
  Vec3 position;            // point and spot
  Vec3 direction{0, 0, -1};  // spot and directional: where the light shines (the node's -Z)
  Rgb intensity{1, 1, 1};   // candela (point, spot) or lux (directional), times colour
  float range = 0;          // 0 = infinite; else the KHR_lights_punctual smooth cut-off distance
  float cos_inner = 1, cos_outer = 0.70710678f;  // spot cone (defaults: 0 and pi/4)
};

// Light arriving from infinitely far away in every direction: a constant colour, or an
// equirectangular (latitude-longitude) map: +Y up, the image's centre column looking down -Z,
// u growing toward +X (counter-clockwise seen from above), row 0 at the zenith.
struct EnvironmentDesc {
  bool present = false;
  Rgb color{1, 1, 1};    // radiance in nits, or the map's multiplier
  int image = -1;        // index into SceneDesc::images (read_image_file, kept compact), or -1 for a constant colour
  float rotation = 0;    // radians about +Y, counter-clockwise seen from above
  std::string source;    // the map's file, for messages and metadata
};

enum class Projection { Perspective, Orthographic };

// A camera placed in the world: it looks down its local -Z axis with +Y up (glTF convention).
struct CameraDesc {
  std::string name;       // the camera's own name, else its node's
  std::string node_name;  // the node that places it
  Projection projection = Projection::Perspective;
  Transform camera_to_world;
  float yfov = 0.8f;                  // perspective: vertical field of view, radians
  std::optional<float> aspect_ratio;  // width / height, when the file gives one
  float xmag = 1.0f, ymag = 1.0f;     // orthographic: half extents
  float znear = 0.0f;
  float zfar = 0.0f;  // 0 = infinite
};

// What a scene contains, so the renderer pays only for what is used.
struct SceneFeatures {
  bool triangles = false;
  bool spheres = false;
  bool instancing = false;  // some mesh is placed more than once
  bool textures = false;
  bool mip_levels = false;  // some image has MIP levels: texture lookups need their footprints
  bool emitters = false;          // emissive surfaces
  bool punctual_lights = false;
  bool environment = false;
  bool transmission = false;     // some material transmits light
  bool thin_sheets = false;      // some of them are thin-walled: shadow rays may pass through
  bool absorbing_media = false;  // some volume absorbs
  bool alpha = false;            // some material is cut out (MASK) or partly transparent (BLEND)
};

struct SceneDesc {
  std::string source;  // the file it came from, for messages
  std::vector<ImageDesc> images;
  std::vector<TextureDesc> textures;
  std::vector<MaterialDesc> materials;
  std::vector<MeshDesc> meshes;
  std::vector<InstanceDesc> instances;
  std::vector<SphereDesc> spheres;
  std::vector<CameraDesc> cameras;  // in node order; the first is the default
  std::vector<PunctualLightDesc> lights;
  EnvironmentDesc environment;

  // The material for index `m`, or the glTF default material for -1 (inline: every bounce asks).
  const MaterialDesc& material(int m) const {
    return m >= 0 && m < static_cast<int>(materials.size()) ? materials[m] : default_material();
  }
  static const MaterialDesc& default_material();
  SceneFeatures features() const;
  size_t triangle_count() const;  // over all instances
  int find_material(const std::string& name) const;  // -1 when absent
  // Objects for AOVs and Cryptomatte: the instances, then the spheres.
  size_t object_count() const { return instances.size() + spheres.size(); }
  std::string object_name(size_t object) const;  // its name, else "instance 3" / "sphere 0"
  // Material ids for AOVs: the materials, then the default material (index materials.size()).
  std::string material_name(size_t id) const;  // its name, else "material 2" / "default"
};

struct Bounds3 {
  Vec3 lo{1e30f}, hi{-1e30f};
  void extend(const Vec3& p) { lo = min(lo, p); hi = max(hi, p); }
  void extend(const Bounds3& b) { lo = min(lo, b.lo); hi = max(hi, b.hi); }
  bool empty() const { return lo.x > hi.x; }
  Vec3 center() const { return (lo + hi) * 0.5f; }
  Vec3 diagonal() const { return hi - lo; }
};

// World-space bounds of all instances and spheres.
Bounds3 scene_bounds(const SceneDesc& scene);

}  // namespace prism
