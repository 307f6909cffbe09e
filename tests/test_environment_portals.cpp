// Environment portals: which sheets are portals, that directions drawn through them have the
// density pdf() says, for one pane and for two panes one behind the other, and that views made in
// SIMD lanes are the scalar ones.
#include <gtest/gtest.h>

#include <cmath>

#include "core/constants.h"
#include "core/environment_portals.h"
#include "core/pcg32.h"
#include "core/sampling.h"
#include "integrators/lane_portal_views.h"
#include "scene_builders.h"
#include "statistics.h"

namespace prism {
namespace {

// A 1 x 1 pane at height z (two triangles), of thin glass.
void add_pane(SceneDesc& desc, float z, int glass) {
  test::add_quad(desc, Vec3(-0.5f, -0.3f, z), Vec3(1, 0, 0), Vec3(0, 1, 0), glass);
}

// The density integrates to 1 over the sphere (uniform directions, 4 pi pdf averaged), and every
// sampled direction has exactly the density pdf() gives it, without help from drawn_in but for
// a few rounding cases on the edges.
void expect_consistent(const EnvironmentPortals& portals, const Vec3& ref) {
  const EnvironmentPortals::View view = portals.view(ref);
  ASSERT_GT(view.total, 0.0f);
  Pcg32 rng(7, 0);
  test::RunningStats integral;
  for (int i = 0; i < 1000000; ++i) {
    const Vec3 w = sample_uniform_sphere(Vec2{rng.next_float(), rng.next_float()});
    integral.add(4 * kPi * portals.pdf(view, ref, w));
  }
  EXPECT_NEAR(integral.mean(), 1.0, test::kSigmas * integral.standard_error());
  int outside = 0;
  for (int i = 0; i < 100000; ++i) {
    const auto s = portals.sample(view, ref, Vec2{rng.next_float(), rng.next_float()});
    ASSERT_TRUE(s);
    EXPECT_NEAR(length(s->w), 1.0f, 1e-5f);
    const float with = portals.pdf(view, ref, s->w, s->triangle), without = portals.pdf(view, ref, s->w);
    EXPECT_GT(with, 0.0f);
    if (without != with) ++outside;
  }
  EXPECT_LE(outside, 10);
}

TEST(EnvironmentPortals, AreTheThinSheetsOnly) {
  SceneDesc desc;
  test::add_quad(desc, Vec3(-5, -5, 0), Vec3(10, 0, 0), Vec3(0, 10, 0), test::add_material(desc, Rgb(0.5f)));
  test::add_box(desc, Vec3(2, 2, 1), Vec3(3, 3, 2), test::add_glass(desc, 1.5f));  // a volume: no portal
  EXPECT_TRUE(EnvironmentPortals(desc).empty());
  add_pane(desc, 2, test::add_glass(desc, 1.5f, Rgb(1.0f), 1.0f, /*thin_walled=*/true));
  EXPECT_EQ(EnvironmentPortals(desc).size(), 2u);
  // So many sheet triangles are more likely glassware than windows: no portals at all.
  const int glass = test::add_glass(desc, 1.5f, Rgb(1.0f), 1.0f, true);
  for (int k = 0; k < EnvironmentPortals::kMaxTriangles / 2; ++k) add_pane(desc, 3.0f + float(k), glass);
  EXPECT_TRUE(EnvironmentPortals(desc).empty());
}

TEST(EnvironmentPortals, DrawDirectionsWithTheDensityTheyReport) {
  SceneDesc desc;
  const int glass = test::add_glass(desc, 1.5f, Rgb(1.0f), 1.0f, true);
  add_pane(desc, 2, glass);
  const EnvironmentPortals one(desc);
  expect_consistent(one, Vec3(0.1f, 0.2f, 0));
  expect_consistent(one, Vec3(3, -1, 1.9f));  // nearly edge-on
  // Double glazing: a direction through both panes is twice as likely.
  add_pane(desc, 2.1f, glass);
  const EnvironmentPortals two(desc);
  expect_consistent(two, Vec3(0.1f, 0.2f, 0));
  const EnvironmentPortals::View view = two.view(Vec3(0.0f));
  EXPECT_NEAR(two.pdf(view, Vec3(0.0f), Vec3(0, 0, 1)), 2 / view.total, 1e-6f / view.total);
  EXPECT_EQ(two.pdf(view, Vec3(0.0f), Vec3(0, 0, -1)), 0.0f);  // behind
}

// portal_views gives the very views of EnvironmentPortals::view, in AVX2 and in SSE pairs: points
// near and far, in a pane's plane and on its corners, for a pane (corners shared) and for seven
// (28 corners, more than the kernel keeps, so some are seen again).
TEST(EnvironmentPortals, ViewsInLanesAreTheScalarOnes) {
  const auto expect_same = [](const EnvironmentPortals::View& a, const EnvironmentPortals::View& b, size_t corners,
                              size_t triangles) {
    for (size_t i = 0; i < corners; ++i) {
      const SphericalTriangle::Corner &x = a.corner(i), &y = b.corner(i);
      ASSERT_EQ(x.p, y.p);
      ASSERT_EQ(x.dir, y.dir);
      ASSERT_EQ(x.distance, y.distance);
      ASSERT_EQ(x.inverse_distance, y.inverse_distance);
    }
    for (size_t t = 0; t < triangles; ++t) ASSERT_EQ(a.solid_angle[t], b.solid_angle[t]) << t;
    ASSERT_EQ(a.total, b.total);
  };
  for (const int panes : {1, 7}) {
    SceneDesc desc;
    const int glass = test::add_glass(desc, 1.5f, Rgb(1.0f), 1.0f, /*thin_walled=*/true);
    for (int k = 0; k < panes; ++k) add_pane(desc, 2.0f + 0.5f * float(k), glass);
    const EnvironmentPortals portals(desc);
    ASSERT_EQ(portals.size(), size_t(2 * panes));
    Pcg32 rng(9, 10);
    int compared = 0;
    for (int round = 0; round < 500; ++round) {
      const int n = 1 + round % 8;
      Vec3 refs[8];
      for (int k = 0; k < n; ++k) {
        const float scale = std::ldexp(1.0f, int(rng.next_u32() % 16) - 6);
        refs[k] = Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f) * scale;
        if (rng.next_float() < 0.1f) refs[k].z = 2.0f;                       // in the first pane's plane
        if (rng.next_float() < 0.05f) refs[k] = Vec3(-0.5f, -0.3f, 2.0f);   // on its corner
      }
      EnvironmentPortals::View avx2[8], sse[8];
      portal_views(portals, refs, n, avx2);
      portal_views(portals, refs, n, sse, false);
      for (int k = 0; k < n; ++k) {
        const EnvironmentPortals::View scalar = portals.view(refs[k]);
        expect_same(avx2[k], scalar, portals.corners().size(), portals.size());
        expect_same(sse[k], scalar, portals.corners().size(), portals.size());
        if (::testing::Test::HasFatalFailure()) return;
        compared += scalar.total > 0;
      }
    }
    EXPECT_GT(compared, 1000);
  }
}

}  // namespace
}  // namespace prism
