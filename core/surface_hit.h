// SurfaceHit: what a ray learned at the first surface it hit, in world space.
#pragma once

#include "core/ray.h"
#include "core/vec3.h"

namespace prism {

struct SurfaceHit {
  float t = 0;
  Vec3 p;          // hit point, recomputed from the primitive (not o + t d)
  Vec3 p_error;    // per-axis bound on the error of p, for offsetting spawned rays
  Vec3 ng;         // unit geometric normal on the front side (winding / outward sphere)
  Vec3 ns;         // unit shading normal (interpolated vertex normals, else ng)
  Vec2 uv;         // TEXCOORD_0 (0,0 when the primitive has none)
  // uv units per unit of length along the surface (the square root of the ratio of the triangle's
  // uv area to its area), for texture footprints; 0 when the material has no textures or no image
  // has MIP levels.
  float uv_per_length = 0;
  // The width of the ray cone that found the hit (0: none), set by the integrator.
  float cone_width = 0;
  Vec3 tangent;    // toward +u, unit; zero when the surface has no uv parameterisation
  float tangent_sign = 1;  // bitangent = sign x cross(ns, tangent) points up the texture image
  int material = -1;
  int object = -1;   // SceneDesc::object_name's index: the instance, or instances + sphere
  int emitter = -1;  // index into Emitters, or -1 when the surface does not emit
  TriangleId triangle;  // the triangle hit; none for spheres, which a ray may meet twice

  // The footprint of the hit's texture lookups in uv units (0: a point).
  float uv_width() const { return cone_width * uv_per_length; }
};

}  // namespace prism
