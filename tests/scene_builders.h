// Scenes built in code for tests: quads, closed boxes, spheres and materials.
#pragma once

#include "core/scene_desc.h"

namespace prism::test {

// Adds a pure Lambertian material (non-metal with IOR 1, so no specular layer); returns its index.
int add_material(SceneDesc& scene, const Rgb& albedo, const Rgb& emission = Rgb(0.0f), bool double_sided = false);

// Adds one primitive as a mesh of its own, placed once by `xf` (the newest instance); returns the
// mesh index.
int add_mesh(SceneDesc& scene, PrimitiveDesc prim, const Transform& xf = Transform());

// Adds a quad (two triangles) with corners c, c+u, c+u+v, c+v as a one-primitive mesh placed by
// `xf`; its front face is along cross(u, v). Returns the mesh index.
int add_quad(SceneDesc& scene, const Vec3& c, const Vec3& u, const Vec3& v, int material,
             const Transform& xf = Transform());

// Adds an axis-aligned box [lo, hi] as one mesh of 12 triangles whose front faces point inward.
int add_inward_box(SceneDesc& scene, const Vec3& lo, const Vec3& hi, int material);

// Adds an axis-aligned box [lo, hi] as one closed mesh whose front faces point outward.
int add_box(SceneDesc& scene, const Vec3& lo, const Vec3& hi, int material);

// Adds a glass material: smooth (unless roughness > 0), transmission 1, white, with a volume
// (refracting and absorbing: sigma_a = -ln(attenuation) / distance) unless thin_walled.
int add_glass(SceneDesc& scene, float ior, const Rgb& attenuation = Rgb(1.0f), float distance = 1.0f,
              bool thin_walled = false, float roughness = 0.0f);

int add_sphere(SceneDesc& scene, const Vec3& center, float radius, int material);

}  // namespace prism::test
