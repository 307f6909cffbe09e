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

// Texture coordinates of the point with outward unit normal n: u = longitude around +Y
// (0.5 at +Z), v = polar angle from +Y, both in [0,1].
Vec2 sphere_uv(const Vec3& n);

// Adds one user geometry holding all `spheres` to `scene` with geometry id `id`. The vector
// must outlive the Embree scene.
void attach_spheres(RTCDevice device, RTCScene scene, const std::vector<SphereDesc>& spheres, unsigned id);

}  // namespace prism
