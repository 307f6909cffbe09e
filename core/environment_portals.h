// EnvironmentPortals: the thin glass sheets through which the sky reaches an interior, for
// sampling the environment through them (portals, as in Bitterli et al. 2015 and Cycles' light
// portals, found here without the user marking them).
#pragma once

#include <new>
#include <optional>
#include <type_traits>
#include <vector>

#include "core/scene_desc.h"
#include "core/spherical_triangle.h"
#include "core/vec3.h"

namespace prism {

// Inside a room lit through a window, most sky directions drawn by the environment's own density
// end on a wall. Drawing them uniformly over the solid angle of the windows instead (each of
// their triangles chosen by the solid angle it subtends, then a direction uniform within it, Arvo
// 1995) finds the sky every time the window is not blocked. The density of a direction is then
// k / total, k the number of portal triangles it crosses, total their summed solid angle.
class EnvironmentPortals {
 public:
  // Larger counts are likely glass objects rather than windows, and every vertex pays per triangle.
  static constexpr int kMaxTriangles = 32;
  static constexpr int kMaxCorners = 3 * kMaxTriangles;

  EnvironmentPortals() = default;
  // The world-space triangles of the scene's thin-sheet primitives (MaterialDesc::is_thin_sheet),
  // or none when there are more than kMaxTriangles of them.
  explicit EnvironmentPortals(const SceneDesc& desc);

  bool empty() const { return triangles_.empty(); }
  size_t size() const { return triangles_.size(); }

  // Below this a triangle is left out of a view, in sampling and density alike: seen edge-on or
  // from very far, its spherical triangle is all rounding.
  static constexpr float kMinSolidAngle = 1e-7f;
  // A triangle's corners, by their index in corners().
  struct Triangle {
    int c0, c1, c2;
  };
  const std::vector<Vec3>& corners() const { return corners_; }  // each point once
  const std::vector<Triangle>& triangles() const { return triangles_; }

  // The portals seen from one point: each corner as seen from it (a corner that triangles share,
  // as a pane's two halves do, is seen once), each triangle's solid angle and their sum.
  struct View {
    float solid_angle[kMaxTriangles];  // set for the portals' triangles only, as the corners are
    float total = 0;  // 0: no portal subtends a usable solid angle from here
    // Raw storage, set for the portals' corners only: zeroing all of it would cost more.
    const SphericalTriangle::Corner& corner(size_t i) const {
      return *std::launder(reinterpret_cast<const SphericalTriangle::Corner*>(corners) + i);
    }
    void set_corner(size_t i, const SphericalTriangle::Corner& c) {
      new (corners + i * sizeof(SphericalTriangle::Corner)) SphericalTriangle::Corner(c);
    }
    alignas(SphericalTriangle::Corner) unsigned char corners[kMaxCorners * sizeof(SphericalTriangle::Corner)];
  };
  View view(const Vec3& ref) const;
  // A direction from ref drawn with density pdf(), and the triangle it was drawn in; nullopt when
  // the view is empty or the draw falls on a degenerate triangle.
  struct Sample {
    Vec3 w;
    int triangle = -1;
  };
  static_assert(std::is_trivially_copyable_v<SphericalTriangle::Corner> &&
                std::is_trivially_destructible_v<SphericalTriangle::Corner>);
  std::optional<Sample> sample(const View& view, const Vec3& ref, Vec2 u) const;
  // Density (per steradian) of sample() drawing unit direction w from ref. drawn_in, the triangle
  // a sample came from, always counts: rounding can put its direction a hair outside its edges.
  float pdf(const View& view, const Vec3& ref, const Vec3& w, int drawn_in = -1) const;

 private:
  std::vector<Vec3> corners_;
  std::vector<Triangle> triangles_;
};

}  // namespace prism
