#include "scene_builders.h"

namespace prism::test {

int add_material(SceneDesc& scene, const Rgb& albedo, const Rgb& emission, bool double_sided) {
  MaterialDesc m;
  m.name = "material " + std::to_string(scene.materials.size());
  m.base_color = albedo;
  m.metallic = 0;
  m.ior = 1.0f;  // no specular layer: a pure Lambertian reflector with this albedo
  m.emissive = emission;
  m.double_sided = double_sided;
  scene.materials.push_back(m);
  return static_cast<int>(scene.materials.size()) - 1;
}

namespace {

void append_quad(PrimitiveDesc& prim, const Vec3& c, const Vec3& u, const Vec3& v) {
  const auto base = static_cast<uint32_t>(prim.positions.size());
  prim.positions.insert(prim.positions.end(), {c, c + u, c + u + v, c + v});
  prim.uvs.insert(prim.uvs.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  prim.indices.insert(prim.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

}  // namespace

int add_mesh(SceneDesc& scene, PrimitiveDesc prim, const Transform& xf) {
  MeshDesc mesh;
  mesh.primitives.push_back(std::move(prim));
  scene.meshes.push_back(std::move(mesh));
  InstanceDesc inst;
  inst.mesh = static_cast<int>(scene.meshes.size()) - 1;
  inst.object_to_world = xf;
  scene.instances.push_back(inst);
  return inst.mesh;
}

int add_quad(SceneDesc& scene, const Vec3& c, const Vec3& u, const Vec3& v, int material, const Transform& xf) {
  PrimitiveDesc prim;
  prim.material = material;
  append_quad(prim, c, u, v);
  return add_mesh(scene, std::move(prim), xf);
}

int add_inward_box(SceneDesc& scene, const Vec3& lo, const Vec3& hi, int material) {
  PrimitiveDesc prim;
  prim.material = material;
  const Vec3 d = hi - lo;
  const Vec3 x(d.x, 0, 0), y(0, d.y, 0), z(0, 0, d.z);
  // cross(u, v) must point into the box for each face.
  append_quad(prim, lo, x, y);            // z = lo.z, normal +z
  append_quad(prim, lo + z, y, x);        // z = hi.z, normal -z
  append_quad(prim, lo, z, x);            // y = lo.y, normal +y
  append_quad(prim, lo + y, x, z);        // y = hi.y, normal -y
  append_quad(prim, lo, y, z);            // x = lo.x, normal +x
  append_quad(prim, lo + x, z, y);        // x = hi.x, normal -x
  return add_mesh(scene, std::move(prim), Transform());
}

int add_box(SceneDesc& scene, const Vec3& lo, const Vec3& hi, int material) {
  const int mesh = add_inward_box(scene, lo, hi, material);
  // Swapping two corners of every triangle turns each face outward.
  auto& idx = scene.meshes[mesh].primitives[0].indices;
  for (size_t t = 0; t + 2 < idx.size(); t += 3) std::swap(idx[t + 1], idx[t + 2]);
  return mesh;
}

int add_glass(SceneDesc& scene, float ior, const Rgb& attenuation, float distance, bool thin_walled, float roughness) {
  MaterialDesc m;
  m.name = "glass " + std::to_string(scene.materials.size());
  m.metallic = 0;
  m.roughness = roughness;
  m.transmission = 1;
  m.ior = ior;
  m.volume = !thin_walled;
  m.attenuation_color = attenuation;
  m.attenuation_distance = distance;
  scene.materials.push_back(m);
  return static_cast<int>(scene.materials.size()) - 1;
}

int add_sphere(SceneDesc& scene, const Vec3& center, float radius, int material) {
  SphereDesc s;
  s.center = center;
  s.radius = radius;
  s.material = material;
  scene.spheres.push_back(s);
  return static_cast<int>(scene.spheres.size()) - 1;
}

}  // namespace prism::test
