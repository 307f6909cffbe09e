// Absorption at the extremes: attenuationDistance 1e-6 to 1e9 and infinity, colour channels of 0
// and 1, path lengths 1e-6 to 1e6: Beer-Lambert transmittance in [0, 1], exact, never NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "materials/medium.h"

namespace prism {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

MaterialDesc absorbing(float colour, float distance) {
  MaterialDesc m;
  m.attenuation_color = Rgb(colour);
  m.attenuation_distance = distance;
  return m;
}

std::vector<float> decades(float from, float to) {
  std::vector<float> v;
  for (float x = from; x <= to * 1.0001f; x *= 10.0f) v.push_back(x);
  return v;
}

// exp(-sigma d) in float against long double: sigma = -ln(c)/D carries a few ulps, so x = sigma d
// carries about 4 ulps relative, and exp(-x) then 4 x ulps relative plus its own rounding.
TEST(AbsorptionExtremes, TransmittanceIsExpMinusSigmaDToFloatAccuracy) {
  int checked = 0;
  for (float colour : {1e-30f, 1e-6f, 0.01f, 0.5f, 0.9f, 0.999999f})
    for (float distance : decades(1e-6f, 1e9f)) {
      const Rgb sigma = absorption_coefficient(absorbing(colour, distance));
      const long double sigma_exact = -std::log(static_cast<long double>(colour)) / distance;
      ASSERT_TRUE(std::isfinite(sigma.x) && sigma.x > 0) << colour << " " << distance;
      ASSERT_NEAR(double(sigma.x), double(sigma_exact), 4e-7 * double(sigma_exact));
      for (float d : decades(1e-6f, 1e6f)) {
        const float t = beer_lambert(sigma, d).x;
        ASSERT_TRUE(t >= 0.0f && t <= 1.0f) << "colour " << colour << " distance " << distance << " d " << d;
        const long double x = sigma_exact * d;
        const long double exact = std::exp(-x);
        const double bound = double(exact) * (4.0 + 4.0 * double(x)) * 0x1p-24 + std::numeric_limits<float>::denorm_min();
        EXPECT_NEAR(double(t), double(exact), bound) << "colour " << colour << " distance " << distance << " d " << d;
        ++checked;
      }
    }
  EXPECT_GT(checked, 500);
}

// The limits the spec leaves implicit: a channel of 1 or an infinite distance absorbs nothing,
// a channel of 0 (or a zero distance) absorbs everything after any positive path, and no path
// at all (d = 0) never absorbs, even then (0 x inf is taken as 0, not NaN).
TEST(AbsorptionExtremes, LimitsAreExactAndNeverNaN) {
  EXPECT_EQ(absorption_coefficient(absorbing(1.0f, 1.0f)).x, 0.0f);
  EXPECT_EQ(absorption_coefficient(absorbing(0.3f, kInf)).x, 0.0f);
  EXPECT_EQ(absorption_coefficient(absorbing(0.0f, 1.0f)).x, kInf);
  EXPECT_EQ(absorption_coefficient(absorbing(0.3f, 0.0f)).x, kInf);
  for (float d : {0.0f, 1e-30f, 1e-6f, 1.0f, 1e6f, kInf}) {
    EXPECT_EQ(beer_lambert(Rgb(0.0f), d), Rgb(1.0f)) << d;
    const Rgb opaque = beer_lambert(Rgb(kInf), d);
    EXPECT_EQ(opaque, d > 0 ? Rgb(0.0f) : Rgb(1.0f)) << d;
    const Rgb mixed = beer_lambert(Rgb(0.0f, 1.0f, kInf), d);
    EXPECT_EQ(mixed.x, 1.0f);
    EXPECT_EQ(mixed.y, d > 0 ? std::exp(-d) : 1.0f);
    EXPECT_EQ(mixed.z, d > 0 ? 0.0f : 1.0f);
  }
  // A NaN length (a broken ray) must not spread: it absorbs nothing rather than poison the path.
  EXPECT_EQ(beer_lambert(Rgb(1.0f), std::numeric_limits<float>::quiet_NaN()), Rgb(1.0f));
  // Out-of-range colours are clamped to [0, 1] as the spec's range requires.
  EXPECT_EQ(absorption_coefficient(absorbing(1.5f, 1.0f)).x, 0.0f);
  EXPECT_EQ(absorption_coefficient(absorbing(-0.5f, 1.0f)).x, kInf);
}

}  // namespace
}  // namespace prism
