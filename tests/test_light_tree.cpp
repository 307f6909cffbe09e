// Light tree: its picks are a probability distribution that matches its pmf, it never misses a
// light that can reach the shading point, and it holds up on degenerate sets of lights.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "chi_square.h"
#include "radiance_stats.h"
#include "core/constants.h"
#include "core/cpu_features.h"
#include "core/emitters.h"
#include "core/light_tree.h"
#include "core/pcg32.h"
#include "core/sampling.h"
#include "integrators/path_integrator.h"
#include "mixed_lights.h"
#include "scene_builders.h"

namespace prism {
namespace {


TEST(LightTree, PicksFormADistributionThatMatchesItsPmf) {
  Pcg32 rng(3, 4);
  const std::vector<LightBounds> lights = mixed_lights(rng, 300);
  const LightTree tree(lights);
  ASSERT_FALSE(tree.empty());
  for (int point = 0; point < 40; ++point) {
    const Vec3 p = random_in_box(rng, 7.0f);
    const Vec3 n = point % 4 == 0 ? Vec3() : random_direction(rng);
    SCOPED_TRACE(::testing::Message() << "point " << point);
    // The pmfs sum to at most 1: where a branch's bounds admit light but neither child's do, the
    // walk finds nothing, which is correct (none of them can light p) and draws nothing.
    std::vector<double> pmf(lights.size() + 1);
    double total = 0;
    for (size_t k = 0; k < lights.size(); ++k) total += pmf[k] = tree.pmf(int(k), p, n);
    EXPECT_EQ(pmf[3], 0.0);
    EXPECT_LE(total, 1.0 + 1e-5);
    EXPECT_GT(total, 0.5);
    pmf.back() = std::max(0.0, 1.0 - total);  // the last bin: nothing drawn

    // Draws land on items (or on nothing) as often as the pmfs say (chi-square, small bins
    // pooled), and each draw reports the pmf that pmf() gives.
    constexpr int kDraws = 200000;
    std::vector<double> observed(pmf.size(), 0.0);
    for (int i = 0; i < kDraws; ++i) {
      const auto pick = tree.sample(p, n, rng.next_float());
      if (!pick) {
        observed.back() += 1;
        continue;
      }
      ASSERT_NEAR(pick->pmf, pmf[size_t(pick->item)], 1e-5 * pmf[size_t(pick->item)]);
      observed[size_t(pick->item)] += 1;
    }
    double chi2 = 0, pooled_observed = 0, pooled_expected = 0;
    int bins = 0;
    for (size_t k = 0; k < pmf.size(); ++k) {
      const double expected = pmf[k] * kDraws;
      if (expected < 5) {
        pooled_observed += observed[k];
        pooled_expected += expected;
        continue;
      }
      chi2 += (observed[k] - expected) * (observed[k] - expected) / expected;
      ++bins;
    }
    if (pooled_expected >= 5) {
      chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
      ++bins;
    }
    ASSERT_GT(bins, 1);
    EXPECT_LT(chi2, test::chi2_critical(bins - 1));
  }
}

// Conservative bounds: wherever some point of a light sends light to a surface, the light can be
// picked; a spot is never picked where it sends nothing. Checked through Emitters, which builds the
// bounds from the scene.
TEST(LightTree, NeverMissesALightThatReachesThePoint) {
  Pcg32 rng(5, 6);
  SceneDesc desc;
  const int one_sided = test::add_material(desc, Rgb(0.0f), Rgb(1.0f));
  const int two_sided = test::add_material(desc, Rgb(0.0f), Rgb(2.0f), true);
  for (int q = 0; q < 40; ++q)
    test::add_quad(desc, random_in_box(rng, 4.0f), random_in_box(rng, 0.6f), random_in_box(rng, 0.6f),
                   q % 3 == 0 ? two_sided : one_sided);
  PunctualLightDesc spot;
  spot.type = LightType::Spot;
  spot.position = Vec3(0, 0, 6);
  spot.direction = Vec3(0, 0, -1);
  spot.cos_inner = std::cos(0.2f);
  spot.cos_outer = std::cos(0.4f);
  desc.lights.push_back(spot);
  const Emitters emitters(desc);
  const int spot_index = int(emitters.size());
  ASSERT_EQ(emitters.size(), 40u);  // each quad one emitter
  int reachable = 0;
  for (int point = 0; point < 400; ++point) {
    const Vec3 p = random_in_box(rng, 6.0f);
    const Vec3 n = random_direction(rng);
    for (int e = 0; e < int(emitters.size()); ++e) {
      const InstanceDesc& inst = desc.instances[size_t(e)];
      const PrimitiveDesc& prim = desc.meshes[size_t(inst.mesh)].primitives[0];
      ASSERT_EQ(emitters.triangle_emitter(e, 0, 0), e);
      ASSERT_EQ(emitters.triangle_emitter(e, 0, 1), e);
      const bool double_sided = desc.materials[size_t(prim.material)].double_sided;
      bool reaches = false;
      for (int s = 0; s < 64 && !reaches; ++s) {
        const uint32_t* idx = &prim.indices[size_t(3 * (s % 2))];  // the quad's two triangles in turn
        const Vec3 a = prim.positions[idx[0]], b = prim.positions[idx[1]], c = prim.positions[idx[2]];
        const Vec3 normal = normalize(cross(b - a, c - a));
        const Vec2 u = sample_uniform_triangle({rng.next_float(), rng.next_float()});
        const Vec3 x = a * u.x + b * u.y + c * (1 - u.x - u.y);
        const float facing = dot(normal, p - x);
        reaches = (facing > 0 || (double_sided && facing < 0)) && dot(n, x - p) != 0;
      }
      if (!reaches) continue;
      ++reachable;
      ASSERT_GT(emitters.pick_probability(e, p, n), 0.0f) << "emitter " << e << " point " << point;
    }
    const Vec3 to_p = normalize(p - spot.position);
    const float spot_pick = emitters.pick_probability(spot_index, p, n);
    const float cos_p = dot(to_p, spot.direction);
    if (cos_p > spot.cos_outer + 1e-4f) {
      EXPECT_GT(spot_pick, 0.0f) << "point " << point;
    } else if (cos_p < spot.cos_outer - 1e-4f) {
      EXPECT_EQ(spot_pick, 0.0f) << "point " << point;
    }
  }
  EXPECT_GT(reachable, 1000);
}

// Emitters::pick_many chooses, for each shading point, the light sample() chooses there: quads and a
// spot in the tree, and a constant sky beside it (chosen first, by power), in batches of every size.
TEST(LightTree, EmittersPickTogetherWhatEachSampleChooses) {
  Pcg32 rng(7, 8);
  SceneDesc desc;
  const int lamp = test::add_material(desc, Rgb(0.0f), Rgb(1.0f));
  for (int q = 0; q < 40; ++q)
    test::add_quad(desc, random_in_box(rng, 4.0f), random_in_box(rng, 0.6f), random_in_box(rng, 0.6f), lamp);
  PunctualLightDesc spot;
  spot.type = LightType::Spot;
  spot.position = Vec3(0, 0, 6);
  spot.direction = Vec3(0, 0, -1);
  spot.intensity = Rgb(30.0f);
  desc.lights.push_back(spot);
  desc.environment.present = true;
  desc.environment.color = Rgb(0.2f);
  const Emitters emitters(desc);
  ASSERT_GT(emitters.tree().depth(), 2);
  int sky = 0, tree = 0;
  for (int round = 0; round < 300; ++round) {
    const int count = 1 + round % 11;
    Vec3 p[11], n[11];
    float u_x[11];
    for (int i = 0; i < count; ++i) {
      p[i] = random_in_box(rng, 6.0f);
      n[i] = random_direction(rng);
      u_x[i] = rng.next_float();
    }
    std::optional<Emitters::Pick> picked[11];
    emitters.pick_many(p, n, u_x, count, picked);
    for (int i = 0; i < count; ++i) {
      const float u_spare = rng.next_float();
      const Vec2 u{u_x[i], rng.next_float()};
      const EmitterSample alone = emitters.sample(p[i], n[i], u_spare, u);
      const EmitterSample given = emitters.sample_light(picked[i], p[i], u_spare, u);
      ASSERT_EQ(given.pdf, alone.pdf) << "round " << round << " point " << i;
      EXPECT_EQ(given.emitter, alone.emitter);
      EXPECT_EQ(given.wi, alone.wi);
      EXPECT_EQ(given.p, alone.p);
      EXPECT_EQ(given.incident, alone.incident);
      (alone.infinite ? sky : tree) += alone.pdf > 0;
    }
  }
  EXPECT_GT(sky, 50);
  EXPECT_GT(tree, 500);
}

// A tree's pick depends on the shading point's normal, so next-event estimation and the MIS weight
// of an emitter found by BSDF sampling must take the pick's probability about the same normal, or
// their weights stop summing to one. A floor whose shading normals lean 50 degrees off its face,
// lit by lamps all around (some near its geometric horizon, some near the shading normal's): direct
// light along a fixed ray, chosen by the tree, must agree with choosing by power, which ignores
// normals.
TEST(LightTree, MultipleImportanceSamplingTakesThePicksOwnNormal) {
  auto scene_for = [](LightSampling how) {
    SceneDesc desc;
    PrimitiveDesc floor;
    floor.material = test::add_material(desc, Rgb(0.8f));
    floor.positions = {Vec3(-5, 0, -5), Vec3(5, 0, -5), Vec3(5, 0, 5), Vec3(-5, 0, 5)};
    floor.indices = {0, 2, 1, 0, 3, 2};  // facing up
    const Vec3 leaning = normalize(Vec3(0, std::cos(0.87f), std::sin(0.87f)));
    floor.normals = {leaning, leaning, leaning, leaning};
    test::add_mesh(desc, std::move(floor));
    const int lamp = test::add_material(desc, Rgb(0.0f), Rgb(4.0f), true);
    // Large and close, so that their light-sampling densities are of the order of the BSDF's and
    // the MIS weights of both strategies matter.
    const Vec3 at[] = {Vec3(-1, 0.2f, 1.5f), Vec3(-1, 0.2f, -1.5f), Vec3(1.5f, 0.2f, -1), Vec3(-2, 1.5f, -1),
                       Vec3(-1, 2, 0)};
    for (const Vec3& c : at) test::add_quad(desc, c, Vec3(2, 0, 0), Vec3(0, 1.2f, 0.8f), lamp);
    return std::make_unique<Scene>(std::move(desc), nullptr, how);
  };
  const auto tree = scene_for(LightSampling::Tree), power = scene_for(LightSampling::Power);
  ASSERT_GT(tree->emitters().tree().depth(), 0);
  const PathIntegrator direct(1, 1 << 20);
  const auto ray_at = [](int) { return Ray{Vec3(0.1f, 1.5f, 0.2f), normalize(Vec3(0.05f, -1, 0.02f))}; };
  const test::RunningStats by_tree = test::radiance_stats(*tree, direct, 200000, {.seed = 3, .channel = 1}, ray_at);
  const test::RunningStats by_power = test::radiance_stats(*power, direct, 200000, {.seed = 4, .channel = 1}, ray_at);
  const double se = std::hypot(by_tree.standard_error(), by_power.standard_error());
  EXPECT_NEAR(by_tree.mean(), by_power.mean(), test::kSigmas * se) << "standard error " << se;
}

// Choosing by power builds no tree (a large emissive mesh would pay seconds for it at start-up)
// and chooses every light by its power alone, wherever it is seen from.
TEST(LightTree, IsNotBuiltWhenLightsAreChosenByPower) {
  Pcg32 rng(9, 10);
  SceneDesc desc;
  const int dim = test::add_material(desc, Rgb(0.0f), Rgb(1.0f));
  const int bright = test::add_material(desc, Rgb(0.0f), Rgb(5.0f));
  for (int q = 0; q < 12; ++q)
    test::add_quad(desc, random_in_box(rng, 4.0f), random_in_box(rng, 0.6f), random_in_box(rng, 0.6f),
                   q % 4 == 0 ? bright : dim);
  const Emitters by_tree(desc, LightSampling::Tree), by_power(desc, LightSampling::Power);
  EXPECT_GT(by_tree.tree().depth(), 0);
  EXPECT_TRUE(by_power.tree().empty());
  EXPECT_EQ(by_power.light_sampling(), LightSampling::Power);
  for (int point = 0; point < 20; ++point) {
    const Vec3 p = random_in_box(rng, 6.0f), n = random_direction(rng);
    for (int e = 0; e < int(by_power.size()); ++e)
      ASSERT_EQ(by_power.pick_probability(e, p, n), by_power.power_pick_probability(e)) << "emitter " << e;
  }
}

// A node is stored as one group of four children or two: sets of 1 to 20 lights give roots of
// every width, some with interior children. In each, every pick reports the pmf that pmf() gives,
// and the picks of a fine stratified sweep of u land on each light in proportion to its pmf.
TEST(LightTree, NodesOfEveryWidthMatchTheirPmf) {
  Pcg32 rng(11, 12);
  for (int count = 1; count <= 20; ++count) {
    SCOPED_TRACE(::testing::Message() << count << " lights");
    std::vector<LightBounds> lights = mixed_lights(rng, std::max(count, 4));
    lights.resize(size_t(count));
    for (LightBounds& b : lights) b.power = std::max(b.power, 1e-3);  // none black here
    const LightTree tree(lights);
    ASSERT_FALSE(tree.empty());
    for (int point = 0; point < 4; ++point) {
      const Vec3 p = random_in_box(rng, 7.0f);
      const Vec3 n = point == 0 ? Vec3() : random_direction(rng);
      std::vector<double> pmf(lights.size());
      double total = 0;
      for (size_t k = 0; k < lights.size(); ++k) total += pmf[k] = tree.pmf(int(k), p, n);
      EXPECT_LE(total, 1.0 + 1e-5) << "point " << point;
      constexpr int kSweep = 1 << 16;
      std::vector<int> hits(lights.size(), 0);
      for (int i = 0; i < kSweep; ++i) {
        const auto pick = tree.sample(p, n, (float(i) + 0.5f) / kSweep);
        if (!pick) continue;
        ASSERT_NEAR(pick->pmf, pmf[size_t(pick->item)], 1e-5 * pmf[size_t(pick->item)]);
        ++hits[size_t(pick->item)];
      }
      // A stratified sweep of u gives each light its share of the unit interval within a few
      // strata for each node on its way down (a child's interval is one piece of its parent's).
      for (size_t k = 0; k < lights.size(); ++k)
        EXPECT_NEAR(hits[k], pmf[k] * kSweep, 8.0) << "light " << k << ", point " << point;
    }
  }
}

TEST(LightTree, HoldsUpOnDegenerateSets) {
  // Many lights alike: one leaf, chosen among by power.
  std::vector<LightBounds> same(100000);
  for (LightBounds& b : same) {
    b.box.extend(Vec3(1, 2, 3));
    b.normals = DirectionCone::every_direction();
    b.power = 1;
  }
  same[777].power = 3;
  const LightTree stacked(same);
  EXPECT_EQ(stacked.depth(), 0);
  EXPECT_NEAR(stacked.pmf(12345, Vec3(0, 0, 0), Vec3(0, 0, 1)), 1.0 / 100002, 1e-11);
  EXPECT_NEAR(stacked.pmf(777, Vec3(0, 0, 0), Vec3(0, 0, 1)), 3.0 / 100002, 1e-11);
  int hits = 0;
  for (int i = 0; i < 100000; ++i) hits += stacked.sample(Vec3(), Vec3(), (float(i) + 0.5f) / 100000)->item == 777;
  EXPECT_EQ(hits, 3);
  // Many lights in one place with different orientations: split by count, as deep as a balanced
  // tree.
  for (size_t k = 0; k < same.size(); ++k) same[k].normals = {normalize(Vec3(1, float(k), 2)), 1.0f};
  EXPECT_LE(LightTree(same).depth(), 17);
  // Lights spread over 30 decades of distance (what scenes/ may span: NUMERICS.md): the
  // surface-area split would peel one light per level; past a depth limit the builder halves by
  // count instead.
  std::vector<LightBounds> spread(2000);
  for (size_t k = 0; k < spread.size(); ++k) {
    spread[k].box.extend(Vec3(std::pow(10.0f, -15.0f + 30.0f * float(k) / float(spread.size())), 0, 0));
    spread[k].normals = DirectionCone::every_direction();
    spread[k].power = 1;
  }
  const LightTree peeled(spread);
  EXPECT_LE(peeled.depth(), 48 + 11);
  double total = 0;
  for (int k = 0; k < int(spread.size()); ++k) total += peeled.pmf(k, Vec3(0.5f, 1, 0), Vec3());
  EXPECT_NEAR(total, 1.0, 1e-4);
  // No light with power: nothing to pick.
  std::vector<LightBounds> dark(3);
  const LightTree none(dark);
  EXPECT_TRUE(none.empty());
  EXPECT_FALSE(none.sample(Vec3(), Vec3(), 0.5f).has_value());
  EXPECT_EQ(none.pmf(1, Vec3(), Vec3()), 0.0f);
}

// A packet's lanes pick their lights together, their walks interleaved level by level: each pick
// must be the one sample() makes alone, bit for bit, in batches of every size (more than eight
// are taken eight at a time), where some walks find no light and some end at a leaf of one light
// or of lights alike, and on a tree that is empty or a single leaf.
TEST(LightTree, PicksTakenTogetherAreThePicksTakenAlone) {
  Pcg32 rng(41, 42);
  std::vector<LightBounds> lights = mixed_lights(rng, 3000);
  for (size_t k = 100; k < 200; ++k) lights[k] = lights[99];  // a leaf of lights alike
  std::vector<LightBounds> alike(5, lights[99]);
  const LightTree trees[] = {LightTree(lights), LightTree(alike), LightTree(std::vector<LightBounds>(2))};
  ASSERT_GT(trees[0].depth(), 5);
  ASSERT_EQ(trees[1].depth(), 0);
  ASSERT_TRUE(trees[2].empty());
  int found = 0, missed = 0;
  for (const LightTree& tree : trees)
    for (int round = 0; round < 400; ++round) {
      const int count = 1 + round % 13;
      Vec3 p[13], n[13];
      float u[13];
      for (int i = 0; i < count; ++i) {
        // Some points far outside the lights, facing away from all of them: nothing reaches them.
        const bool away = rng.next_float() < 0.2f;
        p[i] = away ? Vec3(0, 40, 0) : random_in_box(rng, 7.0f);
        n[i] = away ? Vec3(0, 1, 0) : (i % 5 == 0 ? Vec3() : random_direction(rng));
        u[i] = rng.next_float();
      }
      std::optional<LightTree::Pick> together[13];
      tree.sample_many(p, n, u, count, together);
      for (int i = 0; i < count; ++i) {
        const std::optional<LightTree::Pick> alone = tree.sample(p[i], n[i], u[i]);
        ASSERT_EQ(together[i].has_value(), alone.has_value()) << "round " << round << " lane " << i;
        if (!alone) {
          ++missed;
          continue;
        }
        ++found;
        EXPECT_EQ(together[i]->item, alone->item);
        EXPECT_EQ(std::bit_cast<uint32_t>(together[i]->pmf), std::bit_cast<uint32_t>(alone->pmf));
        EXPECT_EQ(std::bit_cast<uint32_t>(together[i]->remapped), std::bit_cast<uint32_t>(alone->remapped));
      }
    }
  EXPECT_GT(found, 2000);
  EXPECT_GT(missed, 200);
}

// The tree judges a node's children four at a time in SIMD lanes; each lane must give the bits the
// one-group form gives (so sample() and pmf() agree with any scalar reasoning about them), in every
// branch of the formula: points inside a group's sphere and at its centre, groups facing away or
// cut off by their emission angle, two-sided ones, no surface normal, and lanes left unused.
TEST(LightImportance4, EachLaneIsTheOneGroupFormBitForBit) {
  Pcg32 rng(11, 12);
  const std::vector<LightBounds> lights = mixed_lights(rng, 400);
  std::vector<LightImportance> groups;
  for (const LightBounds& b : lights) groups.emplace_back(b, 1e-2);
  groups.emplace_back();  // no power
  int checked = 0, zero = 0, inside = 0;
  for (size_t first = 0; first + 4 <= groups.size(); first += 3) {
    LightImportance4 four;
    const int used = 1 + int(first % 4);  // 1 to 4 lanes set, the rest left without power
    for (int k = 0; k < used; ++k) four.set(k, groups[first + size_t(k)]);
    for (int i = 0; i < 24; ++i) {
      Vec3 p = random_in_box(rng, 6.0f);
      if (i == 0) p = lights[first].box.center();  // at a group's centre: no direction to it
      if (i == 1) p = lights[first].box.center() + 0.1f * (lights[first].box.diagonal());  // inside its sphere
      const Vec3 n = i % 3 == 0 ? Vec3() : random_direction(rng);
      float lanes[4];
      four.evaluate(p, n, lanes);
      for (int k = 0; k < 4; ++k) {
        const float one = k < used ? groups[first + size_t(k)](p, n) : 0.0f;
        ASSERT_EQ(std::bit_cast<uint32_t>(lanes[k]), std::bit_cast<uint32_t>(one))
            << "lane " << k << " of group " << first << " at point " << i << ": " << lanes[k] << " vs " << one;
        ++checked;
        zero += one == 0;
        if (k < used) {
          const Bounds3& box = lights[first + size_t(k)].box;
          inside += length(p - box.center()) < 0.5f * length(box.diagonal());
        }
      }
    }
  }
  // The cases above must all have come up.
  EXPECT_GT(zero, checked / 10);
  EXPECT_GT(checked - zero, checked / 10);
  EXPECT_GT(inside, 0);
}

// A node of eight children is judged in eight AVX lanes where the CPU has AVX2: each half of the
// pair must give the bits its LightImportance4 gives (and so the one-group form's, above), and the
// sum the bits of the tree's pairwise sum of the two.
TEST(LightImportance4, PairsInEightLanesAreTheFourLaneFormBitForBit) {
  if (!cpu_has_avx2()) GTEST_SKIP() << "this CPU has no AVX2";
  Pcg32 rng(13, 14);
  const std::vector<LightBounds> lights = mixed_lights(rng, 400);
  std::vector<LightImportance> groups;
  for (const LightBounds& b : lights) groups.emplace_back(b, 1e-2);
  int checked = 0, zero = 0;
  for (size_t first = 0; first + 8 <= groups.size(); first += 5) {
    LightImportance4 lo, hi;
    const int used = 5 + int(first % 4);  // 5 to 8 lanes set, the rest left without power
    for (int k = 0; k < used; ++k) (k < 4 ? lo : hi).set(k % 4, groups[first + size_t(k)]);
    for (int i = 0; i < 24; ++i) {
      Vec3 p = random_in_box(rng, 6.0f);
      if (i == 0) p = lights[first + 4].box.center();  // at a group's centre: no direction to it
      if (i == 1) p = lights[first + 5].box.center() + 0.1f * (lights[first + 5].box.diagonal());  // inside its sphere
      const Vec3 n = i % 3 == 0 ? Vec3() : random_direction(rng);
      float pair[8], four[8];
      const float sum = evaluate_pair(lo, hi, p, n, pair);
      lo.evaluate(p, n, four);
      hi.evaluate(p, n, four + 4);
      const float four_sum = ((four[0] + four[1]) + (four[2] + four[3])) + ((four[4] + four[5]) + (four[6] + four[7]));
      ASSERT_EQ(std::bit_cast<uint32_t>(sum), std::bit_cast<uint32_t>(four_sum)) << "sum at point " << i;
      for (int k = 0; k < 8; ++k) {
        ASSERT_EQ(std::bit_cast<uint32_t>(pair[k]), std::bit_cast<uint32_t>(four[k]))
            << "lane " << k << " of groups from " << first << " at point " << i << ": " << pair[k] << " vs " << four[k];
        ++checked;
        zero += four[k] == 0;
      }
    }
  }
  EXPECT_GT(zero, checked / 10);
  EXPECT_GT(checked - zero, checked / 10);
}

TEST(DirectionCone, UnionHoldsBothCones) {
  Pcg32 rng(7, 8);
  for (int i = 0; i < 2000; ++i) {
    const DirectionCone a{random_direction(rng), std::cos(kPi * rng.next_float() * rng.next_float())};
    const DirectionCone b{random_direction(rng), std::cos(kPi * rng.next_float() * rng.next_float())};
    const DirectionCone u = cone_union(a, b);
    for (const DirectionCone* c : {&a, &b})
      for (int k = 0; k < 16; ++k) {
        // A direction on the edge of cone c.
        const Vec3 w = random_direction(rng);
        const Vec3 side = normalize(w - c->w * dot(w, c->w));
        const float sin_t = std::sqrt(std::max(0.0f, 1 - c->cos_theta * c->cos_theta));
        const Vec3 edge = c->w * c->cos_theta + side * sin_t;
        ASSERT_GE(dot(edge, u.w), u.cos_theta - 2e-5f) << "pair " << i;
      }
  }
}

}  // namespace
}  // namespace prism
