// SphericalTriangle: the solid angle a triangle subtends from a point, and directions sampled
// uniformly within it (Arvo, "Stratified Sampling of Spherical Triangles", SIGGRAPH 1995).
#pragma once

#include <optional>

#include "core/vec3.h"

namespace prism {

// Barycentric coordinates of a point on a triangle: p = b0 p0 + b1 p1 + b2 p2.
struct Barycentrics {
  float b0 = 0, b1 = 0, b2 = 0;
};

// The triangle (p0, p1, p2) projected onto the unit sphere around `ref`.
class SphericalTriangle {
 public:
  SphericalTriangle(const Vec3& ref, const Vec3& p0, const Vec3& p1, const Vec3& p2);

  // A corner seen from ref: where it is, its distance and the unit direction to it. Triangles that
  // share corners (a quad's two halves) share these too.
  struct Corner {
    Vec3 p, dir;
    float distance = 0, inverse_distance = 0;
  };
  static Corner see(const Vec3& ref, const Vec3& p) {
    Corner c;
    c.p = p;
    const Vec3 d = p - ref;
    c.distance = length(d);
    c.inverse_distance = c.distance > 0 ? 1.0f / c.distance : 0.0f;  // ref on the corner: no direction
    c.dir = d * c.inverse_distance;
    return c;
  }
  SphericalTriangle(const Vec3& ref, const Corner& c0, const Corner& c1, const Corner& c2);

  // The solid angle alone, the very value the constructor gives for these corners, without the
  // rest of its work: what a density or the choice among triangles needs.
  static float solid_angle(const Corner& c0, const Corner& c1, const Corner& c2);
  // The triangle whose solid_angle(c0, c1, c2) is known already: the constructor without the
  // arctangent, the costliest of its steps.
  SphericalTriangle(const Vec3& ref, const Corner& c0, const Corner& c1, const Corner& c2, float known_solid_angle);

  // Two corners seen further apart than this cosine (120 degrees), more so than the other pairs,
  // are relabelled b and c for sampling.
  static constexpr float kRelabelCos = -0.5f;

  // Solid angle in steradians, in [0, 2 pi]; either winding.
  float solid_angle() const { return solid_angle_; }

  // The point where a direction drawn uniformly in the solid angle (pdf 1 / solid_angle())
  // meets the triangle; nullopt when the triangle is degenerate seen from ref.
  std::optional<Barycentrics> sample(Vec2 u) const;

 private:
  Vec3 a_, b_, c_;  // unit directions from ref to p0, p1 and p2, perhaps rotated (kRelabelCos)
  Vec3 e1_, e2_;    // edges p1 - p0 and p2 - p0, divided by ref's largest distance to a corner
  Vec3 o_;          // ref - p0, divided likewise
  float det_ = 0;   // a . (b x c) of the unit directions
  float solid_angle_ = 0;

  // a . (b x c) of the corners' unit directions, and the solid angle from it and the directions'
  // pairwise cosines: the steps the constructor and solid_angle() share.
  static float triple_product(const Corner& c0, const Corner& c1, const Corner& c2);
  static float solid_angle_from(float det, float ab, float bc, float ca);
  // The constructors' work; the solid angle from the corners when `known` is negative.
  void set(const Vec3& ref, const Corner& c0, const Corner& c1, const Corner& c2, float known);
};

}  // namespace prism
