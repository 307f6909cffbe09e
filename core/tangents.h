// Tangent frames for normal mapping, from texture coordinates: per triangle, and per vertex
// for primitives whose files carry no TANGENT attribute.
#pragma once

#include "core/scene_desc.h"

namespace prism {

struct TangentFrame {
  Vec3 tangent;     // dP/du
  Vec3 up_image;    // -dP/dv: glTF's v grows down the image, normal maps' +Y points up it
  bool valid = false;
};

// dP/du and -dP/dv of a triangle from its corners and uvs; invalid for degenerate uvs.
TangentFrame triangle_tangent_frame(const Vec3& p0, const Vec3& p1, const Vec3& p2, Vec2 t0, Vec2 t1, Vec2 t2);

// Fills prim.tangents and prim.tangent_signs from positions, normals and uvs: triangle frames
// accumulated at their vertices, made orthogonal to each vertex normal (Gram-Schmidt), with the
// handedness that makes w cross(n, t) point up the image, as glTF's TANGENT defines. Needs
// normals and uvs; vertices no triangle gives a frame get an arbitrary perpendicular tangent.
void generate_tangents(PrimitiveDesc& prim);

}  // namespace prism
