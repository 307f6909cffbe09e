// Random numbers and warping functions: reference values, determinism, chi-square tests against pdfs.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "core/constants.h"
#include "core/distribution_1d.h"
#include "core/emitters.h"
#include "core/frame.h"
#include "core/pcg32.h"
#include "core/sampler.h"
#include "core/sampling.h"
#include "core/sobol_sampler.h"
#include "core/spherical_triangle.h"
#include "chi_square.h"
#include "scene_builders.h"
#include "solid_angle.h"
#include "statistics.h"

namespace prism {
namespace {

using test::chi2_critical;

using test::chi2;

TEST(Pcg32, MatchesReferenceSequence) {
  // pcg32_srandom_r(&rng, 42, 54) from the PCG reference implementation (pcg32-demo).
  Pcg32 rng(54u, 42u);
  const uint32_t expected[] = {0xa15c02b7, 0x7b47f409, 0xba1d3330, 0x83d2f293, 0xbfa4784b, 0xcbed606e};
  for (uint32_t e : expected) EXPECT_EQ(rng.next_u32(), e);
}

TEST(Pcg32, AdvanceEqualsStepping) {
  Pcg32 a(7, 11), b(7, 11);
  for (int i = 0; i < 1000; ++i) a.next_u32();
  b.advance(1000);
  EXPECT_EQ(a.next_u32(), b.next_u32());
}

TEST(Pcg32, FloatsInUnitInterval) {
  Pcg32 rng(3, 5);
  for (int i = 0; i < 100000; ++i) {
    const float u = rng.next_float();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
  }
}

TEST(IndependentSampler, PureFunctionOfPixelSampleAndDimension) {
  IndependentSampler a(9), b(9), c(10);
  a.start_pixel_sample(3, 4, 17);
  const float a0 = a.next_1d(), a1 = a.next_1d();
  // b visits other pixels first: the values must not depend on history.
  b.start_pixel_sample(5, 5, 2);
  b.next_1d();
  b.start_pixel_sample(3, 4, 17);
  EXPECT_EQ(b.next_1d(), a0);
  EXPECT_EQ(b.next_1d(), a1);
  c.start_pixel_sample(3, 4, 17);
  EXPECT_NE(c.next_1d(), a0);  // another seed, another stream
  a.start_pixel_sample(3, 4, 18);
  EXPECT_NE(a.next_1d(), a0);
  a.start_pixel_sample(4, 3, 17);
  EXPECT_NE(a.next_1d(), a0);
}

TEST(IndependentSampler, UniformAcrossPixels) {
  // The first dimension over many pixels (one sample each) must be uniform.
  IndependentSampler s(0);
  const int bins = 64, n = 64 * 2000;
  std::vector<double> counts(bins, 0), expected(bins, double(n) / bins);
  for (int i = 0; i < n; ++i) {
    s.start_pixel_sample(i % 512, i / 512, 0);
    counts[static_cast<int>(s.next_1d() * bins)] += 1;
  }
  EXPECT_LT(chi2(counts, expected), chi2_critical(bins - 1));
}

TEST(Sampling, CosineHemisphereMatchesPdf) {
  // Under cos(theta)/pi, cos^2(theta) and phi are independent and uniform.
  Pcg32 rng(1, 2);
  const int nb = 16, n = 200000;
  std::vector<double> counts(nb * nb, 0), expected(nb * nb, double(n) / (nb * nb));
  for (int i = 0; i < n; ++i) {
    const Vec3 w = sample_cosine_hemisphere({rng.next_float(), rng.next_float()});
    ASSERT_NEAR(length(w), 1.0f, 1e-5f);
    ASSERT_GE(w.z, 0.0f);
    const double phi = std::atan2(w.y, w.x) + kPi;
    const int a = std::min(nb - 1, static_cast<int>(w.z * w.z * nb));
    const int b = std::min(nb - 1, static_cast<int>(phi / kTwoPi * nb));
    counts[a * nb + b] += 1;
  }
  EXPECT_LT(chi2(counts, expected), chi2_critical(nb * nb - 1));
}

TEST(Sampling, QuarterSinCosMatchesLibm) {
  // Every float step over [-pi/4, pi/4] would be 2e8 cases; a dense grid plus the ends suffices
  // for a polynomial: its error is smooth in a.
  float worst = 0;
  for (int i = -200000; i <= 200000; ++i) {
    const float a = kPiOver4 * (float(i) / 200000.0f);
    const SinCos sc = sin_cos_quarter(a);
    worst = std::max({worst, std::abs(sc.sin - std::sin(a)), std::abs(sc.cos - std::cos(a))});
  }
  EXPECT_LE(worst, 2.0f * 0x1p-24f);  // two ulps of values below 1
  EXPECT_EQ(sin_cos_quarter(0.0f).sin, 0.0f);
  EXPECT_EQ(sin_cos_quarter(0.0f).cos, 1.0f);
}

// Over [0, pi], through the reduction by quarter turns, against double-precision sin and cos: within
// two ulps of values below 1, and within two ulps of sin itself near 0 and pi, where it is small.
TEST(Sampling, HalfTurnSinCosMatchesLibm) {
  float worst = 0, worst_relative = 0;
  std::vector<float> angles = {0.0f, kPiOver4, 0.75f * kPi, kPiOver2, kPi};
  for (const float edge : {kPiOver4, 0.75f * kPi, kPi}) {  // the floats around each switch of k
    float below = edge, above = edge;
    for (int k = 0; k < 4; ++k) {
      angles.push_back(below = std::nextafter(below, 0.0f));
      if (edge < kPi) angles.push_back(above = std::nextafter(above, 4.0f));
    }
  }
  for (int i = 0; i <= 400000; ++i) angles.push_back(kPi * (float(i) / 400000.0f));
  for (float a : {1e-30f, 1e-10f, 1e-4f, kPi - 1e-4f, kPi - 1e-6f}) angles.push_back(a);
  for (const float a : angles) {
    const SinCos sc = sin_cos_half_turn(a);
    const double s = std::sin(double(a)), c = std::cos(double(a));
    worst = std::max({worst, float(std::abs(sc.sin - s)), float(std::abs(sc.cos - c))});
    if (std::abs(s) < 0.25) worst_relative = std::max(worst_relative, float(std::abs(sc.sin - s) / std::abs(s)));
  }
  EXPECT_LE(worst, 2.0f * 0x1p-24f);
  EXPECT_LE(worst_relative, 2.0f * 0x1p-23f);
  EXPECT_EQ(sin_cos_half_turn(0.0f).sin, 0.0f);
  EXPECT_EQ(sin_cos_half_turn(0.0f).cos, 1.0f);
}

TEST(Sampling, ConcentricDiskStaysInsideAndMatchesPolarForm) {
  Pcg32 rng(11, 12);
  for (int i = 0; i < 100000; ++i) {
    const Vec2 u{rng.next_float(), rng.next_float()};
    const Vec2 d = sample_uniform_disk_concentric(u);
    // The textbook form with libm's sin and cos.
    const float ox = 2 * u.x - 1, oy = 2 * u.y - 1;
    const bool wide = std::abs(ox) > std::abs(oy);
    const float r = wide ? ox : oy, theta = wide ? kPiOver4 * (oy / ox) : kPiOver2 - kPiOver4 * (ox / oy);
    ASSERT_NEAR(d.x, r * std::cos(theta), 4e-7f) << u.x << " " << u.y;
    ASSERT_NEAR(d.y, r * std::sin(theta), 4e-7f) << u.x << " " << u.y;
    ASSERT_LE(d.x * d.x + d.y * d.y, 1.0f + 3e-7f);
  }
}

TEST(Sampling, UniformConeMatchesPdf) {
  for (float omc_max : {1e-6f, 0.01f, 0.5f, 2.0f}) {  // from a tiny cone to the whole sphere
    Pcg32 rng(5, 6);
    const int nb = 16, n = 100000;
    std::vector<double> counts(nb * nb, 0), expected(nb * nb, double(n) / (nb * nb));
    for (int i = 0; i < n; ++i) {
      const Vec3 w = sample_uniform_cone({rng.next_float(), rng.next_float()}, omc_max);
      ASSERT_NEAR(length(w), 1.0f, 1e-5f);
      // 1 - cos(theta), computed stably, is uniform on [0, omc_max].
      const double omc = (w.x * w.x + w.y * w.y) / (1.0 + w.z);
      const int a = std::clamp(static_cast<int>(omc / omc_max * nb), 0, nb - 1);
      const int b = std::min(nb - 1, static_cast<int>((std::atan2(w.y, w.x) + kPi) / kTwoPi * nb));
      counts[a * nb + b] += 1;
    }
    EXPECT_LT(chi2(counts, expected), chi2_critical(nb * nb - 1)) << "1 - cos_max = " << omc_max;
  }
}

// Cutting a triangle into k^2 sub-triangles along lines of constant barycentrics, the index of the
// one holding the point with coordinates x = b1, y = b2 (p = p0 + x (p1 - p0) + y (p2 - p0)).
// Cells with i + j < k - 1 hold two sub-triangles; diagonal cells only the lower one.
int sub_triangle_index(double x, double y, int k) {
  const int i = std::clamp(static_cast<int>(x * k), 0, k - 1), j = std::clamp(static_cast<int>(y * k), 0, k - 1);
  const bool upper = (x * k - i) + (y * k - j) >= 1.0;
  int index = 0;
  for (int r = 0; r < j; ++r) index += 2 * (k - r) - 1;
  index += 2 * i + ((upper && i + j < k - 1) ? 1 : 0);
  return std::min(index, k * k - 1);
}

// The corners (as (x, y) pairs in the same coordinates) of the sub-triangles, in index order.
std::vector<std::array<Vec2, 3>> sub_triangles(int k) {
  std::vector<std::array<Vec2, 3>> out;
  const float h = 1.0f / k;
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i + j < k; ++i) {
      const float x = i * h, y = j * h;
      out.push_back({Vec2{x, y}, Vec2{x + h, y}, Vec2{x, y + h}});
      if (i + j < k - 1) out.push_back({Vec2{x + h, y}, Vec2{x + h, y + h}, Vec2{x, y + h}});
    }
  }
  return out;
}

TEST(Sampling, UniformTriangleMatchesArea) {
  // The right triangle (0,0),(1,0),(0,1) cut into k^2 congruent sub-triangles of equal area.
  Pcg32 rng(8, 9);
  const int k = 12, n = 200000;
  std::vector<double> counts(k * k, 0), expected(k * k, double(n) / (k * k));
  for (int s = 0; s < n; ++s) {
    const Vec2 b = sample_uniform_triangle({rng.next_float(), rng.next_float()});
    const float x = b.y, y = 1.0f - b.x - b.y;  // point b0*(0,0) + b1*(1,0) + b2*(0,1)
    ASSERT_GE(x, 0.0f);
    ASSERT_GE(y, -1e-6f);
    counts[size_t(sub_triangle_index(x, y, k))] += 1;
  }
  EXPECT_LT(chi2(counts, expected), chi2_critical(k * k - 1));
}

TEST(Distribution1D, SamplesInProportionToWeights) {
  const std::vector<double> w = {1, 0, 3, 0, 6};
  Distribution1D d(w);
  ASSERT_EQ(d.size(), 5u);
  EXPECT_FLOAT_EQ(d.pmf(0), 0.1f);
  EXPECT_FLOAT_EQ(d.pmf(1), 0.0f);
  EXPECT_FLOAT_EQ(d.pmf(4), 0.6f);
  Pcg32 rng(1, 1);
  std::vector<double> counts(5, 0);
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    float remapped = -1;
    const size_t k = d.sample(rng.next_float(), &remapped);
    ASSERT_GT(d.pmf(k), 0.0f);
    ASSERT_GE(remapped, 0.0f);
    ASSERT_LT(remapped, 1.0f);
    counts[k] += 1;
  }
  const std::vector<double> observed = {counts[0], counts[2], counts[4]};
  const std::vector<double> expected = {0.1 * n, 0.3 * n, 0.6 * n};
  EXPECT_LT(chi2(observed, expected), chi2_critical(2));
}

// sample() inverts the CDF: the item is the last i with cdf(i) <= u, as a binary search over the
// whole CDF finds it, for draws at and beside every CDF value, where a guide slot's bracket could be
// off by one, and for weights with zeros, ties and a peak that takes nearly all the weight.
TEST(Distribution1D, SampleInvertsTheCdfExactly) {
  Pcg32 rng(7, 8);
  std::vector<std::vector<double>> cases = {{1}, {0, 2}, {3, 0}, {1, 1, 1, 1}, {0, 0, 5, 0, 0}};
  for (size_t n : {2u, 3u, 7u, 8u, 9u, 33u, 64u, 100u, 1000u, 2049u}) {
    std::vector<double> w(n);
    for (double& x : w) x = rng.next_float() < 0.3f ? 0.0 : rng.next_float();
    cases.push_back(w);
    w[n / 3] = 1e7;  // a sun
    cases.push_back(w);
  }
  for (const std::vector<double>& w : cases) {
    const Distribution1D d(w);
    ASSERT_GT(d.size(), 0u);
    std::vector<double> cdf(d.size() + 1);
    for (size_t i = 0; i <= d.size(); ++i) cdf[i] = d.cdf(i);
    std::vector<float> draws = {0.0f, 0x1p-149f, 0.5f, kOneMinusEpsilon};
    for (double c : cdf) {
      const float f = static_cast<float>(c);
      for (float v : {f, std::nextafter(f, 0.0f), std::nextafter(f, 1.0f)})
        if (v >= 0 && v < 1) draws.push_back(v);
    }
    for (int k = 0; k < 1000; ++k) draws.push_back(rng.next_float());
    for (float u : draws) {
      const auto above = std::upper_bound(cdf.begin(), cdf.end(), double(u));
      const size_t expected = std::min(size_t(above - cdf.begin()) - 1, d.size() - 1);
      float remapped = -1;
      ASSERT_EQ(d.sample(u, &remapped), expected) << "n " << w.size() << " u " << u;
      ASSERT_GT(d.pmf(expected), 0.0f);
      ASSERT_GE(remapped, 0.0f);
      ASSERT_LT(remapped, 1.0f);
    }
  }
}

// The same for a CDF in floats (an environment map's rows, Distribution2D): the search agrees with
// a search over the float entries, and an item too light for the floats near it to tell apart
// gets an interval of width 0: never drawn, and its pmf 0, so the two stay consistent.
TEST(Distribution1D, FloatCdfInvertsExactlyAndSkipsWhatItCannotResolve) {
  Pcg32 rng(9, 10);
  std::vector<std::vector<double>> cases = {{1e9, 1, 1e9}, {3, 0, 1e-12, 5}};
  for (size_t n : {2u, 17u, 64u, 100u, 2049u}) {
    std::vector<double> w(n);
    for (double& x : w) x = rng.next_float() < 0.3f ? 0.0 : rng.next_float();
    w[n / 3] = 1e9;  // a sun: the other items' intervals shrink to a few float spacings or none
    cases.push_back(w);
  }
  for (const std::vector<double>& w : cases) {
    using Cdf = GuidedCdf<float>;
    std::vector<float> cdf(w.size() + 1);
    ASSERT_GT(Cdf::build_cdf(w.data(), w.size(), cdf.data()), 0.0);
    const size_t slots = Cdf::slots_for(w.size());
    std::vector<uint32_t> guide(slots + 1);
    Cdf::build_guide(cdf.data(), w.size(), guide.data(), slots);
    const Cdf d{cdf.data(), guide.data(), w.size(), slots};
    ASSERT_TRUE(std::is_sorted(cdf.begin(), cdf.end()));
    ASSERT_EQ(cdf.back(), 1.0f);
    std::vector<float> draws = {0.0f, 0.5f, kOneMinusEpsilon};
    for (float c : cdf)
      for (float v : {c, std::nextafter(c, 0.0f), std::nextafter(c, 1.0f)})
        if (v >= 0 && v < 1) draws.push_back(v);
    for (int k = 0; k < 1000; ++k) draws.push_back(rng.next_float());
    for (float u : draws) {
      const size_t expected =
          std::min(size_t(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()) - 1, w.size() - 1);
      float remapped = -1;
      ASSERT_EQ(d.sample(u, &remapped), expected) << "n " << w.size() << " u " << u;
      ASSERT_GT(d.pmf(expected), 0.0f);
      ASSERT_GE(remapped, 0.0f);
      ASSERT_LT(remapped, 1.0f);
    }
  }
  // 1 against 2e9: below float resolution around 0.5, so width 0, in the CDF and in the pmf.
  const std::vector<double> w = {1e9, 1, 1e9};
  std::vector<float> cdf(4);
  GuidedCdf<float>::build_cdf(w.data(), 3, cdf.data());
  EXPECT_EQ((GuidedCdf<float>{cdf.data(), nullptr, 3, 0}.pmf(1)), 0.0f);
}

TEST(Distribution1D, AllZeroIsEmpty) {
  Distribution1D d(std::vector<double>{0, 0, -1, std::nan("")});
  EXPECT_EQ(d.size(), 0u);
  for (size_t i = 0; i < 5; ++i) EXPECT_EQ(d.pmf(i), 0.0f);  // no item has any probability
}

TEST(Frame, IsOrthonormal) {
  Pcg32 rng(2, 3);
  for (int i = 0; i < 10000; ++i) {
    const Vec3 n = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    const Frame f = Frame::from_normal(n);
    ASSERT_NEAR(dot(f.s, f.t), 0.0f, 1e-5f);
    ASSERT_NEAR(dot(f.s, f.n), 0.0f, 1e-5f);
    ASSERT_NEAR(length(f.s), 1.0f, 1e-5f);
    ASSERT_NEAR(length(f.t), 1.0f, 1e-5f);
    const Vec3 v(0.3f, -0.2f, 0.9f);
    const Vec3 back = f.to_world(f.to_local(v));
    ASSERT_NEAR(back.x, v.x, 1e-5f);
    ASSERT_NEAR(back.z, v.z, 1e-5f);
  }
}

using test::triangle_solid_angle;

TEST(SphericalTriangle, SolidAngleMatchesClosedForms) {
  // An octant: pi / 2 from the origin, either winding.
  EXPECT_NEAR(SphericalTriangle(Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)).solid_angle(), kPi / 2, 1e-6f);
  EXPECT_NEAR(SphericalTriangle(Vec3(0.0f), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)).solid_angle(), kPi / 2, 1e-6f);
  // A point just above the interior sees almost a hemisphere.
  EXPECT_NEAR(SphericalTriangle(Vec3(0.2f, 0.2f, 1e-5f), Vec3(-1e3f, -1e3f, 0), Vec3(1e3f, -1e3f, 0), Vec3(0, 1e3f, 0))
                  .solid_angle(),
              kTwoPi, 1e-4f);
  // Small and far: area x cos / d^2, to the precision of the corners (float can't cancel here).
  const float d = 1e4f, side = 1e-2f;
  const SphericalTriangle far(Vec3(0, 0, -d), Vec3(0, 0, 0), Vec3(side, 0, 0), Vec3(0, side, 0));
  EXPECT_NEAR(far.solid_angle(), 0.5 * side * side / (double(d) * d), 1e-3 * 0.5 * side * side / (double(d) * d));
  // In the triangle's plane: nothing.
  EXPECT_EQ(SphericalTriangle(Vec3(2, 2, 0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)).solid_angle(), 0.0f);
}

// SphericalTriangle::solid_angle is the constructor's solid angle, bit for bit, and a triangle made
// with it known samples the very points the plain constructor's does: views that keep only the
// solid angles (Emitters' quads, EnvironmentPortals) draw what they drew when they kept triangles.
TEST(SphericalTriangle, SolidAngleAloneIsTheConstructorsBitForBit) {
  Pcg32 rng(21, 22);
  const auto point = [&](float scale) {
    return Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f) * scale;
  };
  for (int i = 0; i < 20000; ++i) {
    // Near and far, large and tiny, and now and then the reference on a corner (solid angle 0).
    const float scale = std::ldexp(1.0f, int(rng.next_u32() % 24) - 12);
    const Vec3 p0 = point(1), p1 = point(1), p2 = i % 1000 == 0 ? p0 : point(1);
    const Vec3 ref = i % 997 == 0 ? p1 : point(scale);
    const SphericalTriangle::Corner c0 = SphericalTriangle::see(ref, p0), c1 = SphericalTriangle::see(ref, p1),
                                    c2 = SphericalTriangle::see(ref, p2);
    const SphericalTriangle full(ref, c0, c1, c2);
    const float omega = SphericalTriangle::solid_angle(c0, c1, c2);
    ASSERT_EQ(std::bit_cast<uint32_t>(omega), std::bit_cast<uint32_t>(full.solid_angle())) << i;
    const SphericalTriangle known(ref, c0, c1, c2, omega);
    const Vec2 u{rng.next_float(), rng.next_float()};
    const std::optional<Barycentrics> a = full.sample(u), b = known.sample(u);
    ASSERT_EQ(a.has_value(), b.has_value()) << i;
    if (!a) continue;
    ASSERT_EQ(std::bit_cast<uint32_t>(a->b1), std::bit_cast<uint32_t>(b->b1)) << i;
    ASSERT_EQ(std::bit_cast<uint32_t>(a->b2), std::bit_cast<uint32_t>(b->b2)) << i;
  }
}

TEST(SphericalTriangle, SamplesUniformlyInSolidAngle) {
  // Each sub-triangle of a 6 x 6 cut must receive its share of the solid angle, computed on its own
  // corners by the test's own formula. Near, far, grazing, from behind, and a sliver.
  const Vec3 p0(0, 0, 0), p1(1, 0, 0), p2(0.3f, 1, 0);
  struct Case {
    Vec3 ref, q0, q1, q2;
  };
  const Case cases[] = {{Vec3(0.4f, 0.3f, 0.02f), p0, p1, p2}, {Vec3(0.2f, 0.1f, 1.0f), p0, p1, p2},
                        {Vec3(2.5f, 2.0f, 0.15f), p0, p1, p2}, {Vec3(0.6f, -0.3f, -0.4f), p0, p1, p2},
                        {Vec3(0.5f, 0.01f, 0.03f), p0, p1, Vec3(0.5f, 0.02f, 0)}};
  const int k = 6, n = 200000;
  const std::vector<std::array<Vec2, 3>> subs = sub_triangles(k);
  for (const Case& c : cases) {
    const SphericalTriangle st(c.ref, c.q0, c.q1, c.q2);
    const Vec3 e1 = c.q1 - c.q0, e2 = c.q2 - c.q0;
    auto corner = [&](Vec2 b) { return c.q0 + e1 * b.x + e2 * b.y - c.ref; };
    const double total = triangle_solid_angle(c.q0 - c.ref, c.q1 - c.ref, c.q2 - c.ref);
    ASSERT_NEAR(st.solid_angle(), total, 1e-5 * total);
    std::vector<double> counts(subs.size(), 0), expected;
    for (const auto& t : subs) expected.push_back(n * triangle_solid_angle(corner(t[0]), corner(t[1]), corner(t[2])) / total);
    Pcg32 rng(11, 12);
    for (int i = 0; i < n; ++i) {
      const std::optional<Barycentrics> b = st.sample({rng.next_float(), rng.next_float()});
      ASSERT_TRUE(b.has_value());
      ASSERT_GE(b->b0, -1e-6f);
      ASSERT_GE(b->b1, 0.0f);
      ASSERT_GE(b->b2, 0.0f);
      ASSERT_NEAR(b->b0 + b->b1 + b->b2, 1.0f, 1e-6f);
      counts[size_t(sub_triangle_index(b->b1, b->b2, k))] += 1;
    }
    EXPECT_LT(chi2(counts, expected), chi2_critical(int(subs.size()) - 1)) << "ref " << c.ref.x << " " << c.ref.y << " " << c.ref.z;
  }
}

TEST(Emitters, TrianglePdfIntegratesToSolidAngle) {
  // E[1 / pdf] over emitter samples is the solid angle the emitter subtends, whether a triangle
  // is sampled by solid angle (near, and grazing) or by area (far), and pdf() agrees with sample().
  SceneDesc scene;
  const int light = test::add_material(scene, Rgb(0.0f), Rgb(1.0f));
  const Vec3 c(-0.5f, -0.25f, 1.0f), u(1.0f, 0, 0), v(0, 0.5f, 0);
  test::add_quad(scene, c, v, u, light);  // front face (cross(v, u) = -z) toward the points below
  Emitters emitters(scene);
  ASSERT_EQ(emitters.size(), 1u);  // the quad is one emitter
  for (const Vec3 ref : {Vec3(0.2f, 0.1f, 0.0f), Vec3(0.2f, 0.1f, -2.0f), Vec3(3.0f, 0.1f, 0.95f)}) {
    Pcg32 rng(4, 4);
    test::RunningStats stats;
    for (int i = 0; i < 200000; ++i) {
      const EmitterSample s = emitters.sample(ref, Vec3(), rng.next_float(), {rng.next_float(), rng.next_float()});
      ASSERT_GT(s.pdf, 0.0f);
      ASSERT_NEAR(s.p.z, 1.0f, 1e-6f);
      ASSERT_NEAR(emitters.pdf(s.emitter, ref, Vec3(), s.p, s.n), s.pdf, 1e-4f * s.pdf);
      stats.add(1.0 / s.pdf);
    }
    const double expected = triangle_solid_angle(c - ref, c + u - ref, c + u + v - ref) +
                            triangle_solid_angle(c - ref, c + u + v - ref, c + v - ref);
    EXPECT_NEAR(stats.mean(), expected, test::kSigmas * stats.standard_error() + 1e-6 * expected) << "ref z " << ref.z;
  }
}

TEST(Emitters, APixelsLightPointsAreStratifiedOverAllOfALightsTriangles) {
  // A light of several triangles: Emitters::sample chooses among them with the first coordinate
  // of its 2D draw and places the point with what is left of it, so a pixel's Sobol samples, a
  // (0,2)-net in that draw, stay stratified over the light as a whole. Count 256 of them in 4 x 4
  // cells of equal expected count: for independent points the counts' chi-square follows
  // chi2(15), whose mean over 32 pixels is 15 with a standard deviation of sqrt(2 x 15 / 32) =
  // 0.97. Stratified points must come under a quarter of that (11.6 standard deviations below). Choosing
  // the triangle by a draw of its own, as prism did before, handed each of a quad's two triangles
  // a random half of the points: 11.1 from afar and 13.0 close by. The lights: a rectangle cut
  // into four triangles around its centre, chosen by power (by area, so that from afar the points
  // are uniform over the rectangle), and the same rectangle as two triangles, which are one quad
  // emitter (its unit square maps linearly onto it from afar). Placing the fan's points with a
  // draw of their own gives 7.0 here.
  const Vec3 c(-0.5f, -0.25f, 1.0f), u(1.0f, 0, 0), v(0, 0.5f, 0);
  for (const bool fan : {true, false}) {
    SceneDesc scene;
    const int light = test::add_material(scene, Rgb(0.0f), Rgb(1.0f));
    if (fan) {
      PrimitiveDesc prim;
      prim.material = light;
      prim.positions = {c + (u + v) * 0.5f, c, c + v, c + u + v, c + u};
      prim.indices = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1};  // front faces toward -z, as the quad's
      test::add_mesh(scene, std::move(prim));
    } else {
      test::add_quad(scene, c, v, u, light);
    }
    Emitters emitters(scene, fan ? LightSampling::Power : LightSampling::Tree);
    ASSERT_EQ(emitters.size(), fan ? 4u : 1u);
    // From afar (area sampling) and from close by (sampling by solid angle, whose cells are not
    // those of area: there the counts are weighed against the solid angle each cell subtends).
    for (const Vec3 ref : {Vec3(0.2f, 0.1f, -2.0f), Vec3(0.2f, 0.1f, 0.7f)}) {
      // Close by, the fan's triangles are each uniform in solid angle, but chosen by area.
      if (fan && ref.z > 0) continue;
      std::vector<double> expected(16);
      double total_solid_angle = 0;
      for (int cell = 0; cell < 16; ++cell) {
        const Vec3 lo = c + u * (float(cell % 4) / 4) + v * (float(cell / 4) / 4), du = u / 4, dv = v / 4;
        const Vec3 centre = lo + (du + dv) * 0.5f, to = centre - ref;
        const double cosine = std::abs(to.z) / length(to);
        // Afar: evenly by area (the quad's pdf, in area measure, says so).
        expected[size_t(cell)] =
            ref.z < 0 ? (fan ? 1.0 : emitters.pdf(0, ref, Vec3(), centre, Vec3(0, 0, -1)) * cosine / length_squared(to))
                      : triangle_solid_angle(lo - ref, lo + du - ref, lo + du + dv - ref) +
                            triangle_solid_angle(lo - ref, lo + du + dv - ref, lo + dv - ref);
        total_solid_angle += expected[size_t(cell)];
      }
      constexpr int kSamples = 256, kPixels = 32;
      for (double& e : expected) e *= kSamples / total_solid_angle;  // the total of whichever measure
      SobolSampler sampler(9);
      double mean_chi2 = 0;
      for (int pixel = 0; pixel < kPixels; ++pixel) {
        std::vector<double> counts(16);
        for (int i = 0; i < kSamples; ++i) {
          sampler.start_pixel_sample(pixel, 7, uint64_t(i));
          const VertexSamples draws = sampler.next_vertex();
          const EmitterSample s = emitters.sample(ref, Vec3(), draws.light_spare, draws.light_point);
          ASSERT_GT(s.pdf, 0.0f);
          const int x = std::clamp(int((s.p.x - c.x) / u.x * 4), 0, 3);
          const int y = std::clamp(int((s.p.y - c.y) / v.y * 4), 0, 3);
          counts[size_t(4 * y + x)] += 1;
        }
        mean_chi2 += chi2(counts, expected) / kPixels;
      }
      EXPECT_LT(mean_chi2, 15.0 / 4) << (fan ? "fan" : "quad") << ", ref z " << ref.z;
      std::printf("%s, ref z %g: mean chi-square %.3f\n", fan ? "fan of four" : "quad", double(ref.z), mean_chi2);
    }
  }
}

TEST(Emitters, BackOfSingleSidedTriangleSpendsNoSample) {
  // Seen from behind, a single-sided emitter sends nothing: no sample, and a pdf of 0 to match.
  // A double-sided one is sampled from both sides, by solid angle near it and by area far away.
  for (const bool double_sided : {false, true}) {
    SceneDesc scene;
    const int light = test::add_material(scene, Rgb(0.0f), Rgb(1.0f), double_sided);
    test::add_quad(scene, Vec3(-0.5f, -0.25f, 1.0f), Vec3(0, 0.5f, 0), Vec3(1.0f, 0, 0), light);  // faces -z
    Emitters emitters(scene);
    for (const Vec3 ref : {Vec3(0.1f, 0.0f, 1.5f), Vec3(0.1f, 0.0f, 9.0f), Vec3(0.1f, 0.0f, 0.5f)}) {
      const bool lit = double_sided || ref.z < 1.0f;
      Pcg32 rng(3, 3);
      for (int i = 0; i < 100; ++i) {
        const EmitterSample s = emitters.sample(ref, Vec3(), rng.next_float(), {rng.next_float(), rng.next_float()});
        EXPECT_EQ(s.pdf > 0, lit) << "double-sided " << double_sided << ", ref z " << ref.z;
        const Vec3 p(0.1f, 0.0f, 1.0f), n(0, 0, -1);
        EXPECT_EQ(emitters.pdf(0, ref, Vec3(), p, n) > 0, lit);
      }
    }
  }
}

TEST(Emitters, SphereConeSamplingIsUniformInSolidAngle) {
  for (float distance : {1.5f, 10.0f, 1e4f}) {
    SceneDesc scene;
    const int light = test::add_material(scene, Rgb(0.0f), Rgb(1.0f));
    test::add_sphere(scene, Vec3(0, 0, distance), 1.0f, light);
    Emitters emitters(scene);
    const Vec3 ref(0, 0, 0);
    const double sin2 = 1.0 / (double(distance) * distance);
    const double omc_max = sin2 / (1.0 + std::sqrt(1.0 - sin2));
    Pcg32 rng(6, 7);
    const int nb = 10, n = 100000;
    std::vector<double> counts(nb * nb, 0), expected(nb * nb, double(n) / (nb * nb));
    for (int i = 0; i < n; ++i) {
      const EmitterSample s = emitters.sample(ref, Vec3(), rng.next_float(), {rng.next_float(), rng.next_float()});
      ASSERT_NEAR(s.pdf, 1.0 / (2.0 * kPi * omc_max), 1e-3 / (2.0 * kPi * omc_max));
      // The point lies on the sphere, on the side that faces ref.
      ASSERT_NEAR(length(s.p - Vec3(0, 0, distance)), 1.0f, 1e-5f * distance);
      ASSERT_LE(dot(s.n, s.p - ref), 1e-3f * distance);
      const Vec3 w = normalize(s.p - ref);
      const double omc = (double(w.x) * w.x + double(w.y) * w.y) / (1.0 + w.z);
      const int a = std::clamp(static_cast<int>(omc / omc_max * nb), 0, nb - 1);
      const int b = std::min(nb - 1, static_cast<int>((std::atan2(w.y, w.x) + kPi) / kTwoPi * nb));
      counts[a * nb + b] += 1;
    }
    if (distance < 100.0f) {  // beyond that, float directions cannot resolve the cone's bins
      EXPECT_LT(chi2(counts, expected), chi2_critical(nb * nb - 1)) << "distance " << distance;
    }
  }
}

TEST(Sampling, PowerHeuristic) {
  EXPECT_FLOAT_EQ(power_heuristic(1, 1), 0.5f);
  EXPECT_FLOAT_EQ(power_heuristic(3, 1), 0.9f);
  EXPECT_FLOAT_EQ(power_heuristic(0, 0), 0.0f);
  EXPECT_FLOAT_EQ(power_heuristic(std::numeric_limits<float>::infinity(), 1), 1.0f);
}

}  // namespace
}  // namespace prism
