// Samplers: Sobol's construction and stratification, determinism, uniformity, independence between
// pixels, and the convergence rate each sampler gives on the furnace.
#include <gtest/gtest.h>
#include <array>

#include <cmath>
#include <cstdio>
#include <memory>
#include <set>

#include "core/camera.h"
#include "core/owen_sobol.h"
#include "core/owen_sobol_vertex.h"
#include "core/pcg32.h"
#include "core/renderer.h"
#include "core/sampler_factory.h"
#include "core/scene.h"
#include "core/sobol_sampler.h"
#include "furnace_scene.h"
#include "integrators/path_integrator.h"
#include "statistics.h"

namespace prism {
namespace {

// A vertex's seven coordinates, in the order a sampler draws them.
std::array<float, 7> coordinates(const VertexSamples& v) {
  return {v.light_spare, v.light_point.x, v.light_point.y, v.lobe, v.direction.x, v.direction.y, v.roulette};
}

TEST(Sobol, TablesMatchTheDirectionNumbers) {
  Pcg32 rng(5, 6);
  for (int i = 0; i < 10000; ++i) {
    const uint32_t index = i < 64 ? uint32_t(i) : rng.next_u32();
    ASSERT_EQ(reverse_bits(sobol_dim1_reversed(reverse_bits(index))), sobol_dim1(index)) << index;
  }
  // The first points of dimension 1: 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8 (Joe and Kuo's tables).
  const double expected[8] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  for (uint32_t i = 0; i < 8; ++i) EXPECT_EQ(sobol_dim1(i) * 0x1p-32, expected[i]) << i;
}

// The table-free form the AVX2 lanes use: every index bit alone, then random indices.
TEST(Sobol, SupersetTransformMatchesTheDirectionNumbers) {
  for (int k = 0; k < 32; ++k) {
    uint32_t x = 1u << k;
    reversed_sobol_dim1_in_place(x);
    ASSERT_EQ(x, reverse_bits(sobol_dim1(1u << k))) << "index bit " << k;
  }
  Pcg32 rng(11, 12);
  for (int i = 0; i < 10000; ++i) {
    uint32_t x = rng.next_u32();
    const uint32_t index = x;
    reversed_sobol_dim1_in_place(x);
    ASSERT_EQ(x, reverse_bits(sobol_dim1(index))) << index;
  }
}

TEST(Sobol, PairedReversalReversesEachHalf) {
  Pcg32 rng(7, 8);
  for (int i = 0; i < 10000; ++i) {
    const uint32_t hi = rng.next_u32(), lo = rng.next_u32();
    const uint64_t r = reverse_bits64((uint64_t(hi) << 32) | lo);
    ASSERT_EQ(uint32_t(r >> 32), reverse_bits(lo)) << hi << " " << lo;
    ASSERT_EQ(uint32_t(r), reverse_bits(hi)) << hi << " " << lo;
  }
  static_assert(reverse_bits64(1) == 0x8000000000000000ull);
}

TEST(Sobol, OwenScrambleKeepsDyadicIntervals) {
  // Values sharing their top k bits still share them after scrambling, and it is a bijection.
  Pcg32 rng(1, 9);
  for (int trial = 0; trial < 2000; ++trial) {
    const uint32_t seed = rng.next_u32(), a = rng.next_u32();
    const int k = int(rng.next_u32() % 32);
    const uint32_t mask = k ? ~0u << (32 - k) : 0u;
    const uint32_t b = (a & mask) | (rng.next_u32() & ~mask);
    ASSERT_EQ(owen_scramble(a, seed) & mask, owen_scramble(b, seed) & mask);
  }
  std::set<uint32_t> seen;
  for (uint32_t v = 0; v < 4096; ++v) seen.insert(owen_scramble(v << 20, 0xdeadbeef) >> 20);
  EXPECT_EQ(seen.size(), 4096u);
}

// Whether the first n points put exactly n / 2^(m - t) in every dyadic box of volume 2^(t - m)
// (a (t,m,s)-net: every split of m - t halvings among the s axes), for points in [0, 1)^s.
template <size_t S>
bool is_net(const std::vector<std::array<float, S>>& points, int m, int t) {
  const size_t n = size_t(1) << m, boxes = size_t(1) << (m - t);
  std::array<int, S> split{};
  while (true) {
    int used = 0;
    for (size_t a = 0; a + 1 < S; ++a) used += split[a];
    if (used <= m - t) {
      split[S - 1] = m - t - used;
      std::vector<size_t> count(boxes, 0);
      for (size_t i = 0; i < n; ++i) {
        size_t box = 0;
        for (size_t a = 0; a < S; ++a) box = (box << split[a]) | size_t(points[i][a] * float(1 << split[a]));
        if (++count[box] > n / boxes) return false;
      }
    }
    size_t a = 0;  // the next split of the first S - 1 axes, odometer order
    while (a + 1 < S && ++split[a] > m - t) split[a++] = 0;
    if (a + 1 == S) return true;
  }
}

// The first 2^m samples of a pixel put exactly one point in every dyadic box of area 2^-m in every
// 2D draw (a (0,m,2)-net: every shape 2^-a x 2^-(m-a)), and one in every 1/2^m interval in 1D draws.
TEST(Sobol, EveryDrawOfAPixelIsStratified) {
  SobolSampler sampler(42);
  for (int m : {2, 4, 6, 8}) {
    const uint32_t n = 1u << m;
    for (int pixel = 0; pixel < 6; ++pixel) {
      const int x = pixel * 37, y = 1000 - pixel * 11;
      const int pairs = 6;  // alternating 2D and 1D draws, as a path makes them
      std::vector<std::array<float, 2>> planes[pairs];
      std::vector<std::array<float, 1>> lines[pairs];
      for (uint32_t s = 0; s < n; ++s) {
        sampler.start_pixel_sample(x, y, s);
        for (int d = 0; d < pairs; ++d) {
          const Vec2 p = sampler.next_2d();
          planes[d].push_back({p.x, p.y});
          lines[d].push_back({sampler.next_1d()});
          for (const float v : {p.x, p.y, lines[d].back()[0]}) {
            ASSERT_GE(v, 0.0f);
            ASSERT_LT(v, 1.0f);
          }
        }
      }
      for (int d = 0; d < pairs; ++d) {
        EXPECT_TRUE(is_net(planes[d], m, 0)) << "m " << m << ", pixel " << pixel << ", 2D draw " << d;
        EXPECT_TRUE(is_net(lines[d], m, 0)) << "m " << m << ", pixel " << pixel << ", 1D draw " << d;
      }
    }
  }
}

// A vertex's light point and the bounce that reached the vertex (the camera's jitter for the first
// vertex) are one 4D point set: the first 2^m samples of a pixel form a (3,m,4)-net in them, while
// each stays a (0,m,2)-net alone. Two draws padded independently are no such net: here the light
// points of consecutive vertices, which are not drawn together.
TEST(Sobol, LightPointsMakeOneNetWithTheBounceBefore) {
  SobolSampler sampler(17);
  for (int m = 3; m <= 10; ++m) {
    const uint32_t n = 1u << m;
    for (int pixel = 0; pixel < 3; ++pixel) {
      std::vector<std::array<float, 4>> joint[3], apart;
      std::vector<std::array<float, 2>> light[3];
      for (uint32_t s = 0; s < n; ++s) {
        sampler.start_pixel_sample(pixel * 13, 7 - pixel, s);
        Vec2 before = sampler.next_2d();  // the camera's jitter
        Vec2 first_light;
        for (int k = 0; k < 3; ++k) {
          const VertexSamples v = sampler.next_vertex();
          joint[k].push_back({before.x, before.y, v.light_point.x, v.light_point.y});
          light[k].push_back({v.light_point.x, v.light_point.y});
          if (k == 1) apart.push_back({first_light.x, first_light.y, v.light_point.x, v.light_point.y});
          first_light = v.light_point;
          before = v.direction;
        }
      }
      for (int k = 0; k < 3; ++k) {
        EXPECT_TRUE(is_net(joint[k], m, 3)) << "m " << m << ", pixel " << pixel << ", vertex " << k;
        EXPECT_TRUE(is_net(light[k], m, 0)) << "m " << m << ", pixel " << pixel << ", vertex " << k;
      }
      if (m >= 6) EXPECT_FALSE(is_net(apart, m, 3)) << "m " << m << ", pixel " << pixel;
    }
  }
}

// A sample's values depend only on (pixel, sample index, dimension, seed), never on what the
// sampler was asked before: any order of pixels and samples gives the same numbers.
TEST(Samplers, ValuesDependOnlyOnPixelIndexAndDimension) {
  for (const std::string& name : sampler_names()) {
    auto a = make_sampler(name, 9), b = make_sampler(name, 9), other_seed = make_sampler(name, 10);
    a->start_pixel_sample(3, 4, 17);
    std::vector<float> direct;
    for (int d = 0; d < 40; ++d) direct.push_back(d % 3 == 0 ? a->next_2d().y : a->next_1d());
    for (int s = 0; s < 30; ++s) {  // disturb b's state: other pixels, other samples, partial paths
      b->start_pixel_sample(s % 5, 4, uint64_t(s));
      for (int d = 0; d < s; ++d) b->next_1d();
    }
    b->start_pixel_sample(3, 4, 17);
    other_seed->start_pixel_sample(3, 4, 17);
    int same_as_other_seed = 0;
    for (int d = 0; d < 40; ++d) {
      const float v = d % 3 == 0 ? b->next_2d().y : b->next_1d();
      EXPECT_EQ(v, direct[size_t(d)]) << name << " dimension " << d;
      same_as_other_seed += (d % 3 == 0 ? other_seed->next_2d().y : other_seed->next_1d()) == direct[size_t(d)];
    }
    EXPECT_LT(same_as_other_seed, 3) << name << ": another seed must give other numbers";
  }
}

// A sampler moved to a position (PathIntegrator's continuations move theirs) draws what one started
// at that sample index would after as many draws: from a position it stood at, from another index,
// and after draws of another pixel's sample in between (Sobol's lanes share their seed caches).
TEST(Samplers, MovingToAPositionDrawsWhatStartingThereWould) {
  for (const std::string& name : sampler_names()) {
    const std::vector<std::unique_ptr<Sampler>> lanes = make_lane_samplers(name, 4, 2);
    auto fresh = make_sampler(name, 4);
    for (const uint64_t index : {uint64_t(0), uint64_t(5), uint64_t(1) << 20}) {
      Sampler& moved = *lanes[0];
      moved.start_pixel_sample(7, 2, 3);
      moved.next_2d();
      const SamplerPosition at = moved.position();
      EXPECT_EQ(at.index, 3u) << name;
      lanes[1]->start_pixel_sample(8, 2, 9);  // another pixel, through the shared cache
      for (int d = 0; d < 12; ++d) lanes[1]->next_1d();
      for (int d = 0; d < 30; ++d) moved.next_1d();
      moved.move_to({index, at.dimension});
      fresh->start_pixel_sample(7, 2, index);
      fresh->next_2d();
      ASSERT_EQ(moved.position().index, index) << name;
      ASSERT_EQ(moved.position().dimension, fresh->position().dimension) << name;
      for (int vertex = 0; vertex < 14; ++vertex) {  // past Sobol's 64 cached dimensions
        const std::array<float, 7> a = coordinates(moved.next_vertex()), b = coordinates(fresh->next_vertex());
        for (int c = 0; c < 7; ++c) ASSERT_EQ(a[c], b[c]) << name << " index " << index << " vertex " << vertex;
      }
    }
  }
}

// A path vertex's five draws taken at once (eight lanes wide on AVX2 CPUs, for Sobol) are the
// values the same draws give one at a time, bit for bit, across pixels, sample indices (up to the
// top bit) and dimensions (past the seed cache's 64), after a 1D draw or none. Sobol's light point
// is the one draw that is not next_2d's (Sobol.LightPointsMakeOneNetWithTheBounceBefore).
TEST(Samplers, VertexDrawsMatchDrawsOneAtATime) {
  std::printf("owen_sobol_vertex: %s\n", owen_sobol_vertex_available() ? "AVX2 lanes" : "one draw at a time");
  for (const std::string& name : sampler_names()) {
    auto batched = make_sampler(name, 21), single = make_sampler(name, 21);
    SobolSampler* const sobol = dynamic_cast<SobolSampler*>(single.get());
    Pcg32 rng(8, 9);
    for (int trial = 0; trial < 400; ++trial) {
      const int x = int(rng.next_u32() % 64), y = int(rng.next_u32() % 64);
      const uint64_t index = trial < 200 ? uint64_t(trial) : rng.next_u32();
      batched->start_pixel_sample(x, y, index);
      single->start_pixel_sample(x, y, index);
      if (trial % 2 == 1) ASSERT_EQ(batched->next_1d(), single->next_1d()) << name << " trial " << trial;
      for (int vertex = 0; vertex < 18; ++vertex) {  // 90 dimensions
        const std::array<float, 7> at_once = coordinates(batched->next_vertex());
        if (sobol) {
          VertexSamples v;
          sobol->draw_vertex_one_at_a_time(v);
          const std::array<float, 7> one_by_one = coordinates(v);
          for (int c = 0; c < 7; ++c)
            ASSERT_EQ(at_once[c], one_by_one[c]) << "trial " << trial << " vertex " << vertex << " coordinate " << c;
          continue;
        }
        const float light_spare = single->next_1d();
        const Vec2 light_point = single->next_2d();
        const float lobe = single->next_1d();
        const Vec2 direction = single->next_2d();
        const float one_by_one[7] = {light_spare, light_point.x, light_point.y, lobe,
                                     direction.x, direction.y,   single->next_1d()};
        for (int c = 0; c < 7; ++c)
          ASSERT_EQ(at_once[c], one_by_one[c]) << name << " trial " << trial << " vertex " << vertex << " coordinate " << c;
      }
      // The draw after the vertices continues where they ended.
      ASSERT_EQ(batched->next_1d(), single->next_1d()) << name << " trial " << trial;
    }
  }
}

// A packet's lane samplers share work between lanes in the same pixel (Sobol's seed cache), yet
// each draws what a sampler of its own would: here lanes start mixes of up to eight pixels per
// packet, come back to pixels they left, and reach different depths, past the 64 cached dimensions.
TEST(Samplers, LaneSamplersDrawWhatLoneSamplersDraw) {
  for (const std::string& name : sampler_names()) {
    constexpr int kLanes = 8;
    const std::vector<std::unique_ptr<Sampler>> lanes = make_lane_samplers(name, 33, kLanes);
    ASSERT_EQ(lanes.size(), size_t(kLanes));
    auto lone = make_sampler(name, 33);
    Pcg32 rng(4, 7);
    for (int packet = 0; packet < 300; ++packet) {
      const int pixels = 1 + int(rng.next_u32() % kLanes);  // distinct pixels in this packet
      int x[kLanes], y[kLanes], depth[kLanes];
      uint64_t index[kLanes];
      for (int k = 0; k < kLanes; ++k) {
        const int p = int(rng.next_u32() % uint32_t(pixels)) + packet % 3;  // overlaps the last packets' pixels
        x[k] = p % 4;
        y[k] = p / 4;
        index[k] = rng.next_u32() % 64;
        depth[k] = 1 + int(rng.next_u32() % 16);  // vertices: up to 81 dimensions
        lanes[size_t(k)]->start_pixel_sample(x[k], y[k], index[k]);
      }
      std::vector<std::array<float, 7>> drawn[kLanes];
      for (int vertex = 0; vertex < 16; ++vertex)  // lanes advance together, as in a packet
        for (int k = 0; k < kLanes; ++k)
          if (vertex < depth[k]) drawn[k].push_back(coordinates(lanes[size_t(k)]->next_vertex()));
      for (int k = 0; k < kLanes; ++k) {
        lone->start_pixel_sample(x[k], y[k], index[k]);
        for (size_t vertex = 0; vertex < drawn[k].size(); ++vertex) {
          const std::array<float, 7> expected = coordinates(lone->next_vertex());
          for (size_t c = 0; c < 7; ++c)
            ASSERT_EQ(drawn[k][vertex][c], expected[c])
                << name << " packet " << packet << " lane " << k << " vertex " << vertex << " coordinate " << c;
        }
      }
    }
  }
}

// A lane that stays on one pixel keeps its seeds while the other lanes run through many pixels.
TEST(Samplers, LaneSamplerKeepsItsPixelWhileOthersMoveOn) {
  for (const std::string& name : sampler_names()) {
    const std::vector<std::unique_ptr<Sampler>> lanes = make_lane_samplers(name, 2, 8);
    auto lone = make_sampler(name, 2);
    lanes[0]->start_pixel_sample(9, 9, 3);
    lone->start_pixel_sample(9, 9, 3);
    std::vector<float> expected;
    for (int i = 0; i < 40; ++i) expected.push_back(lone->next_1d());
    for (int i = 0; i < 40; ++i) {
      for (int k = 1; k < 8; ++k) {
        lanes[size_t(k)]->start_pixel_sample(i * 8 + k, 0, 0);
        lanes[size_t(k)]->next_2d();
      }
      ASSERT_EQ(lanes[0]->next_1d(), expected[size_t(i)]) << name << " dimension " << i;
    }
  }
}

// A copy of a sampler goes on drawing what the original would, from caches of its own.
TEST(Samplers, CopiedSobolSamplerContinuesAlone) {
  const std::vector<std::unique_ptr<Sampler>> lanes = make_lane_samplers("sobol", 5, 2);
  auto& original = static_cast<SobolSampler&>(*lanes[0]);
  original.start_pixel_sample(6, 2, 11);
  original.next_vertex();
  SobolSampler copy(original);
  lanes[1]->start_pixel_sample(1, 1, 0);  // the shared cache moves on
  original.start_pixel_sample(0, 0, 0);
  SobolSampler lone(5);
  lone.start_pixel_sample(6, 2, 11);
  lone.next_vertex();
  for (int d = 0; d < 70; ++d) ASSERT_EQ(copy.next_1d(), lone.next_1d()) << "dimension " << d;
}

// Pooled over pixels, every dimension is uniform, and a 1D draw is independent of the next one
// (chi-square over a 16 x 16 grid; a correct sampler's statistic has mean 255 and deviation 22.6;
// stratification can only lower it).
TEST(Samplers, DimensionsAreUniformAndIndependentAcrossPixels) {
  for (const std::string& name : sampler_names()) {
    auto sampler = make_sampler(name, 3);
    constexpr int kBins = 16, kDraws = 10;
    std::vector<std::vector<double>> hist(kDraws, std::vector<double>(kBins * kBins, 0.0));
    double n = 0;
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 48; ++x)
        for (int s = 0; s < 8; ++s, ++n) {
          sampler->start_pixel_sample(x, y, uint64_t(s));
          for (int d = 0; d < kDraws; ++d) {
            const Vec2 p = d % 2 == 0 ? sampler->next_2d() : Vec2{sampler->next_1d(), sampler->next_1d()};
            hist[size_t(d)][size_t(int(p.y * kBins) * kBins + int(p.x * kBins))] += 1;
          }
        }
    const double expected = n / (kBins * kBins), dof = kBins * kBins - 1;
    for (int d = 0; d < kDraws; ++d) {
      double chi2 = 0;
      for (double h : hist[size_t(d)]) chi2 += (h - expected) * (h - expected) / expected;
      EXPECT_LT(chi2, dof + test::kSigmas * std::sqrt(2 * dof)) << name << " draw " << d;
    }
  }
}

// A flat field shows no structure: the errors of neighbouring pixels are uncorrelated (the sample
// correlation of n independent pairs has standard deviation 1/sqrt(n)).
TEST(Samplers, NoCorrelationBetweenPixelsInAFlatField) {
  const int size = 64;
  for (const std::string& name : sampler_names()) {
    const std::vector<double> e = test::furnace_errors(name, 4, size, 5);
    for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}, std::pair{1, 1}, std::pair{2, 0}, std::pair{0, 4}}) {
      double sab = 0, saa = 0, sbb = 0, sa = 0, sb = 0, n = 0;
      for (int y = 0; y + dy < size; ++y)
        for (int x = 0; x + dx < size; ++x, ++n) {
          const double a = e[size_t(y * size + x)], b = e[size_t((y + dy) * size + x + dx)];
          sa += a, sb += b, sab += a * b, saa += a * a, sbb += b * b;
        }
      const double cov = sab / n - sa / n * sb / n;
      const double rho = cov / std::sqrt((saa / n - sa / n * sa / n) * (sbb / n - sb / n * sb / n));
      EXPECT_LT(std::abs(rho), test::kSigmas / std::sqrt(n)) << name << " lag " << dx << "," << dy;
    }
  }
}

// Monte Carlo error falls as 1/sqrt(N): four times the samples halve the RMSE. Sobol must do at
// least as well (its low dimensions converge faster). The ratio's tolerance comes from the
// measured spread of the squared errors (the two renders share samples, which only tightens it).
TEST(Samplers, FourTimesTheSamplesHalveTheFurnaceError) {
  const int size = 40;
  for (const std::string& name : sampler_names()) {
    for (int n : {4, 16}) {
      const auto [r1, s1] = test::rmse_with_error(test::furnace_errors(name, n, size, 77));
      const auto [r4, s4] = test::rmse_with_error(test::furnace_errors(name, 4 * n, size, 77));
      const double ratio = r4 / r1;
      const double sigma = ratio * std::hypot(s1 / r1, s4 / r4);
      if (name == "independent") EXPECT_NEAR(ratio, 0.5, test::kSigmas * sigma) << name << " at " << n << " spp";
      else EXPECT_LT(ratio, 0.5 + test::kSigmas * sigma) << name << " at " << n << " spp";
      std::printf("%s: RMSE %.5f at %d spp, %.5f at %d spp, ratio %.3f +- %.3f\n", name.c_str(), r1, n, r4, 4 * n, ratio,
                  sigma);
    }
  }
}

}  // namespace
}  // namespace prism
