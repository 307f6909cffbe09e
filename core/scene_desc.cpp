#include "core/scene_desc.h"

#include <algorithm>
#include <string>

namespace prism {

const MaterialDesc& SceneDesc::default_material() {
  // glTF 2.0 §3.9.6: the default material is one with no properties specified, so every
  // property takes its schema default (MaterialDesc's initialisers).
  static const MaterialDesc kDefault = [] {
    MaterialDesc d;
    d.name = "(default)";
    return d;
  }();
  return kDefault;
}

SceneFeatures SceneDesc::features() const {
  SceneFeatures f;
  std::vector<int> uses(meshes.size(), 0);
  for (const auto& inst : instances) {
    if (inst.mesh < 0 || inst.mesh >= static_cast<int>(meshes.size())) continue;
    if (++uses[inst.mesh] > 1) f.instancing = true;
    for (const auto& prim : meshes[inst.mesh].primitives) {
      if (prim.triangle_count() > 0) f.triangles = true;
      if (material(prim.material).is_emissive()) f.emitters = true;
    }
  }
  f.spheres = !spheres.empty();
  f.punctual_lights = !lights.empty();
  f.environment = environment.present;
  for (const ImageDesc& image : images)
    if (!image.mips.empty()) f.mip_levels = true;
  for (const auto& s : spheres)
    if (material(s.material).is_emissive()) f.emitters = true;
  for (const MaterialDesc& m : materials) {
    for (const TextureRef* r : m.texture_slots())
      if (r->present()) f.textures = true;
    if (m.is_transmissive()) f.transmission = true;
    if (m.is_thin_sheet()) f.thin_sheets = true;
    if (m.has_alpha()) f.alpha = true;
    if (m.has_volume() && (m.attenuation_distance < std::numeric_limits<float>::infinity()) &&
        min(m.attenuation_color, Rgb(1.0f)) != Rgb(1.0f))
      f.absorbing_media = true;
  }
  return f;
}

size_t SceneDesc::triangle_count() const {
  size_t n = 0;
  for (const auto& inst : instances)
    if (inst.mesh >= 0 && inst.mesh < static_cast<int>(meshes.size()))
      for (const auto& prim : meshes[inst.mesh].primitives) n += prim.triangle_count();
  return n;
}

int SceneDesc::find_material(const std::string& name) const {
  for (size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == name) return static_cast<int>(i);
  return -1;
}

std::string SceneDesc::object_name(size_t object) const {
  if (object < instances.size())
    return instances[object].name.empty() ? "instance " + std::to_string(object) : instances[object].name;
  const size_t s = object - instances.size();
  return s < spheres.size() && !spheres[s].name.empty() ? spheres[s].name : "sphere " + std::to_string(s);
}

std::string SceneDesc::material_name(size_t id) const {
  if (id >= materials.size()) return "default";
  return materials[id].name.empty() ? "material " + std::to_string(id) : materials[id].name;
}

Bounds3 scene_bounds(const SceneDesc& scene) {
  Bounds3 b;
  for (const auto& inst : scene.instances) {
    if (inst.mesh < 0 || inst.mesh >= static_cast<int>(scene.meshes.size())) continue;
    for (const auto& prim : scene.meshes[inst.mesh].primitives)
      for (const auto& p : prim.positions) b.extend(inst.object_to_world.point(p));
  }
  for (const auto& s : scene.spheres) {
    b.extend(s.center - Vec3(s.radius));
    b.extend(s.center + Vec3(s.radius));
  }
  return b;
}

}  // namespace prism
