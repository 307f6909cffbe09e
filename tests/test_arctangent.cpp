// atan2_fast against the exact angle (std::atan2 in double): within 3 ulp everywhere, and the
// special values of std::atan2.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "core/arctangent.h"
#include "core/pcg32.h"

namespace prism {
namespace {

// The error of `got` in units in the last place of the float nearest to `exact`.
double ulps(float got, double exact) {
  const float nearest = static_cast<float>(exact);
  const double ulp = std::nextafter(std::abs(nearest), std::numeric_limits<float>::infinity()) - std::abs(nearest);
  return std::abs(double(got) - exact) / ulp;
}

// A float of magnitude 2^-40 to 2^40 and random sign.
float random_magnitude(Pcg32& rng) {
  const float m = std::ldexp(rng.next_float() + 0.5f, int(rng.next_u32() % 81) - 40);
  return rng.next_float() < 0.5f ? -m : m;
}

TEST(Arctangent, WithinThreeUlpOfTheExactAngle) {
  Pcg32 rng(2026, 12);
  double worst = 0;
  for (int i = 0; i < 2000000; ++i) {
    // Magnitudes from 2^-40 to 2^40, every sign, and ratios near 0, 1 and tan(pi / 8) as often as any.
    const float x = random_magnitude(rng), y0 = random_magnitude(rng);
    float y = y0;
    if (i % 4 == 1) y = x * (0.9f + 0.2f * rng.next_float());
    if (i % 4 == 2) y = x * (0.4f + 0.03f * rng.next_float());
    const double e = ulps(atan2_fast(y, x), std::atan2(double(y), double(x)));
    worst = std::max(worst, e);
    ASSERT_LE(e, 3.0) << "atan2(" << y << ", " << x << ")";
  }
  std::printf("worst error: %.3f ulp\n", worst);
}

TEST(Arctangent, SpecialValuesAreStdAtan2s) {
  const float inf = std::numeric_limits<float>::infinity();
  const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-45f, -3e38f, inf, -inf};
  for (const float y : values)
    for (const float x : values) {
      const float want = std::atan2(y, x);
      EXPECT_NEAR(atan2_fast(y, x), want, 4e-7f * std::abs(want)) << "atan2(" << y << ", " << x << ")";
      EXPECT_EQ(std::signbit(atan2_fast(y, x)), std::signbit(want)) << "atan2(" << y << ", " << x << ")";
    }
  EXPECT_TRUE(std::isnan(atan2_fast(std::nanf(""), 1.0f)));
  EXPECT_TRUE(std::isnan(atan2_fast(1.0f, std::nanf(""))));
}

}  // namespace
}  // namespace prism
