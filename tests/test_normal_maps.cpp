// Normal mapping: generated tangent frames, the bent shading normal, and handedness under mirroring.
#include <gtest/gtest.h>

#include <cmath>

#include "core/scene.h"
#include "core/tangents.h"
#include "materials/material_eval.h"
#include "scene_builders.h"

namespace prism {
namespace {

// A quad in the z = 0 plane facing +z, with u along +x and v growing toward -y (image rows
// downward), as a texture lies when viewed from the front.
PrimitiveDesc front_quad(bool mirror_u) {
  PrimitiveDesc p;
  p.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  p.normals.assign(4, Vec3(0, 0, 1));
  const float u0 = mirror_u ? 1.0f : 0.0f, u1 = mirror_u ? 0.0f : 1.0f;
  p.uvs = {{u0, 1}, {u1, 1}, {u1, 0}, {u0, 0}};
  p.indices = {0, 1, 2, 0, 2, 3};
  return p;
}

TEST(Tangents, GeneratedFramePointsAlongUAndUpTheImage) {
  for (bool mirror : {false, true}) {
    PrimitiveDesc p = front_quad(mirror);
    generate_tangents(p);
    ASSERT_EQ(p.tangents.size(), 4u);
    for (size_t i = 0; i < 4; ++i) {
      EXPECT_NEAR(p.tangents[i].x, mirror ? -1.0f : 1.0f, 1e-6f);
      // bitangent = w cross(n, t) must point up the image, which is +y here.
      const Vec3 b = cross(p.normals[i], p.tangents[i]) * p.tangent_signs[i];
      EXPECT_NEAR(b.y, 1.0f, 1e-6f) << "mirror " << mirror;
    }
  }
}

// A material whose normal map is one texel: a normal tilted 45 degrees toward +x (tangent space).
int tilted_normal_material(SceneDesc& desc, float scale = 1.0f) {
  ImageDesc img;
  img.width = img.height = 1;
  img.channels = 3;
  const float s = std::sqrt(0.5f);
  img.texels = {0.5f + 0.5f * s, 0.5f, 0.5f + 0.5f * s};
  desc.images.push_back(img);
  desc.textures.push_back({0});
  MaterialDesc m;
  m.normal_texture.texture = 0;
  m.normal_scale = scale;
  desc.materials.push_back(m);
  return static_cast<int>(desc.materials.size()) - 1;
}

Vec3 bent_normal_at(const Scene& scene, const Vec3& origin) {
  SurfaceHit hit;
  EXPECT_TRUE(scene.intersect(Ray{origin, Vec3(0, 0, -1)}, hit));
  return shading_normal(scene.desc(), scene.desc().material(hit.material), hit);
}

TEST(NormalMaps, BendTheShadingNormalInTheTangentFrame) {
  for (bool mirror : {false, true}) {
    SceneDesc desc;
    const int m = tilted_normal_material(desc);
    PrimitiveDesc p = front_quad(mirror);
    p.material = m;
    generate_tangents(p);
    desc.meshes.push_back({"quad", {p}});
    desc.instances.push_back({"quad", 0, Transform()});
    const Scene scene(std::move(desc));
    const Vec3 n = bent_normal_at(scene, Vec3(0.2f, 0.1f, 1));
    // Tilted toward +u: toward +x, or -x where u is mirrored.
    EXPECT_NEAR(n.x, mirror ? -std::sqrt(0.5f) : std::sqrt(0.5f), 1e-4f);
    EXPECT_NEAR(n.z, std::sqrt(0.5f), 1e-4f);
  }
}

TEST(NormalMaps, ScaleFlattensAndPerTriangleFramesWork) {
  SceneDesc desc;
  const int m = tilted_normal_material(desc, 0.0f);  // scale 0: x and y vanish, the normal is unbent
  PrimitiveDesc p = front_quad(false);
  p.material = m;  // no tangents: the triangle's own frame is used
  desc.meshes.push_back({"quad", {p}});
  desc.instances.push_back({"quad", 0, Transform()});
  const Scene scene(std::move(desc));
  const Vec3 n = bent_normal_at(scene, Vec3(0.2f, 0.1f, 1));
  EXPECT_NEAR(n.z, 1.0f, 1e-5f);
}

TEST(NormalMaps, MirroredInstancesKeepBitangentsUpTheImage) {
  // The same quad placed twice: as is, and mirrored in x (reused mesh: a real instance). In the
  // mirror image, +u runs toward -x, so the bent normal must lean toward -x.
  SceneDesc desc;
  const int m = tilted_normal_material(desc);
  PrimitiveDesc p = front_quad(false);
  p.material = m;
  generate_tangents(p);
  desc.meshes.push_back({"quad", {p}});
  desc.instances.push_back({"a", 0, Transform::translate(Vec3(-3, 0, 0))});
  desc.instances.push_back({"b", 0, Transform::translate(Vec3(3, 0, 0)) * Transform::scale(Vec3(-1, 1, 1))});
  const Scene scene(std::move(desc));
  EXPECT_NEAR(bent_normal_at(scene, Vec3(-3, 0.1f, 1)).x, std::sqrt(0.5f), 1e-4f);
  EXPECT_NEAR(bent_normal_at(scene, Vec3(3, 0.1f, 1)).x, -std::sqrt(0.5f), 1e-4f);
}

}  // namespace
}  // namespace prism
