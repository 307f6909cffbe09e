// Analytic spheres for Embree as user geometry, intersected in each sphere's own frame in double.
#pragma once

#include <embree3/rtcore.h>

#include <vector>

#include "core/ray.h"
#include "core/scene_desc.h"

namespace prism {

// Nearest t in (t_min, t_max) where the ray meets the sphere, or a negative value on a miss.
// Solves in double with the discriminant of Hearn and Baker (r^2 - |f|^2, f the offset of the
// closest approach; Haines et al., "Precision Improvements for Ray/Sphere Intersection",
// Ray Tracing Gems ch. 7), which stays exact for tiny spheres far from the ray origin.
double intersect_sphere(const Vec3& center, float radius, const Ray& ray);

// Both roots t0 <= t1 of the ray meeting the sphere (any sign); false when it misses.
bool sphere_roots(const Vec3& center, float radius, const Ray& ray, double& t0, double& t1);

// Spheres for Embree, with what their callbacks need to honour alphaMode: keep(owner, sphere,
// uv, ray, t) decides whether a root is a hit (nullptr: every sphere is opaque).
struct SphereGeometry {
  const std::vector<SphereDesc>* spheres = nullptr;
  const void* owner = nullptr;
  bool (*keep)(const void* owner, int sphere, Vec2 uv, const Ray& ray, float t) = nullptr;
};

// Texture coordinates of the point with outward unit normal n: u = longitude around +Y
// (0.5 at +Z), v = polar angle from +Y, both in [0,1].
Vec2 sphere_uv(const Vec3& n);

// Adds one user geometry holding all spheres to `scene` with geometry id `id`. `geometry` and
// what it points to must outlive the Embree scene.
void attach_spheres(RTCDevice device, RTCScene scene, const SphereGeometry& geometry, unsigned id);

}  // namespace prism
