// Environment portals: which sheets are portals, and that directions drawn through them have the
// density pdf() says, for one pane and for two panes one behind the other.
#include <gtest/gtest.h>

#include <cmath>

#include "core/constants.h"
#include "core/environment_portals.h"
#include "core/pcg32.h"
#include "core/sampling.h"
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

}  // namespace
}  // namespace prism
