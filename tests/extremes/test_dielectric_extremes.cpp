// Dielectrics at the extremes: IOR 1 to 4 and below 1, incidence up to 89.999 degrees, and the
// neighbourhood of the critical angle (Fresnel accuracy, R + T = 1, refraction agreeing with TIR).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/constants.h"
#include "materials/dielectric_bxdf.h"
#include "materials/fresnel.h"

namespace prism {
namespace {

// The indices of the matrix; each is also met from inside (eta below 1).
const std::vector<float> kIors = {1.0f, 1.0001f, 1.33f, 1.5f, 2.42f, 4.0f};

// Exact unpolarised Fresnel reflectance in long double, for cos_i > 0 seen from the side whose
// relative index (n_other / n_this) is eta.
long double exact_fresnel(long double cos_i, long double eta) {
  if (eta == 1.0L) return 0.0L;
  const long double sin2_t = (1.0L - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0L) return 1.0L;
  const long double cos_t = std::sqrt(1.0L - sin2_t);
  const long double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const long double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5L * (rs * rs + rp * rp);
}

// Cosines to test: 0 to 89.999 degrees evenly, plus a dense sweep either side of the critical
// angle (when there is one) down to 1e-7 radians from it.
std::vector<float> test_cosines(float eta) {
  std::vector<float> cosines;
  const double max_theta = 89.999 * kPi / 180.0;
  for (int i = 0; i <= 20000; ++i) cosines.push_back(float(std::cos(max_theta * i / 20000.0)));
  if (eta < 1.0f) {
    const double critical = std::asin(double(eta));
    for (double d = 1e-1; d > 1e-7; d *= 0.8)
      for (double s : {-1.0, 1.0})
        if (critical + s * d < kPi / 2) cosines.push_back(float(std::cos(critical + s * d)));
    cosines.push_back(float(std::cos(critical)));
  }
  return cosines;
}

// Backward stability: the float reflectance equals the exact reflectance of a cosine within 4
// ulps of the one given (plus 1e-6 absolute for the rounding of the result). Near the critical
// angle R is steep (1 - R grows like the square root of the distance to it), so this is the
// bound a float input can promise; a formula that first forms 1 - cos^2 loses far more there.
TEST(DielectricExtremes, FresnelIsExactForANearbyInputAtEveryAngleAndIndex) {
  for (float n : kIors)
    for (float eta : {n, 1.0f / n}) {
      double worst = 0;
      for (float c : test_cosines(eta)) {
        const float r = fresnel_dielectric(c, eta);
        ASSERT_TRUE(std::isfinite(r) && r >= 0.0f && r <= 1.0f) << "eta " << eta << " cos " << c;
        long double lo = 2, hi = -1;
        for (int ulps = -4; ulps <= 4; ++ulps) {
          float cp = c;
          for (int k = 0; k < std::abs(ulps); ++k) cp = std::nextafter(cp, ulps < 0 ? 0.0f : 1.0f);
          const long double e = exact_fresnel(cp, eta);
          lo = std::min(lo, e);
          hi = std::max(hi, e);
        }
        const double outside = double(std::max({lo - r, r - hi, 0.0L}));
        worst = std::max(worst, outside);
        EXPECT_LE(outside, 1e-6) << "eta " << eta << " cos " << c << ": R " << r << ", exact in [" << double(lo)
                                 << ", " << double(hi) << "]";
      }
      RecordProperty("worst_" + std::to_string(eta), std::to_string(worst));
    }
}

// The same interface from either side: fresnel(-cos, eta) is fresnel(cos, 1 / eta).
TEST(DielectricExtremes, BackSideUsesTheInverseIndex) {
  for (float n : kIors)
    for (float c : test_cosines(1.0f / n)) EXPECT_EQ(fresnel_dielectric(-c, n), fresnel_dielectric(c, 1.0f / n)) << n;
}

// Refraction exists exactly where Fresnel says some light is transmitted, and the refracted
// direction is a unit vector obeying Snell's law.
TEST(DielectricExtremes, RefractionAgreesWithTotalInternalReflection) {
  for (float n : kIors)
    for (float eta : {n, 1.0f / n})
      for (float c : test_cosines(eta)) {
        const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
        const Vec3 wo(s, 0.0f, c);
        Vec3 wt;
        const bool refracted = refract(wo, Vec3(0, 0, 1), eta, wt);
        const float r = fresnel_dielectric(c, eta);
        // Whenever Fresnel transmits anything, the refracted direction exists (R may round to 1
        // a hair before the critical angle, where refraction still exists: that is harmless).
        if (r < 1.0f) {
          ASSERT_TRUE(refracted) << "eta " << eta << " cos " << c << " R " << r;
        }
        if (!refracted) continue;
        EXPECT_NEAR(length(wt), 1.0f, 1e-5f);
        EXPECT_LE(wt.z, 0.0f);
        // Snell: n_i sin_i = n_t sin_t, i.e. sin_t = sin_i / eta (the tangential part is -wo_t / eta).
        EXPECT_NEAR(wt.x, -s / eta, 2e-6f * std::max(1.0f, s / eta)) << "eta " << eta << " cos " << c;
      }
}

// A smooth interface splits light into R and T with R + T = 1 (radiance scaled by 1/eta^2 on
// refraction, undone here), at every angle, from both sides, never NaN.
TEST(DielectricExtremes, SmoothInterfaceConservesEnergy) {
  for (float n : kIors)
    for (float c : test_cosines(1.0f / n))
      for (float side : {1.0f, -1.0f}) {
        const DielectricBxdf glass(n, 0.0f, Rgb(1.0f), DielectricBxdf::Mode::Volume);
        const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
        const Vec3 wo(s, 0.0f, side * c);
        if (wo.z == 0) continue;
        // The value of a delta lobe is f |cos|; transmitted radiance carries 1/eta^2, undone here.
        auto weight = [&](const BxdfSample& b) {
          const double w = double(b.f.x) * std::abs(b.wi.z) * (b.transmission ? double(b.eta) * b.eta : 1.0);
          EXPECT_TRUE(std::isfinite(w) && w >= 0) << "ior " << n << " cos " << c;
          return w;
        };
        // u_lobe = 0 picks reflection and u_lobe -> 1 transmission, whenever each has weight.
        double total = 0;
        if (const auto r = glass.sample(wo, 0.0f, Vec2{0.5f, 0.5f}); r && !r->transmission) total += weight(*r);
        if (const auto t = glass.sample(wo, 0x1.fffffep-1f, Vec2{0.5f, 0.5f}); t && t->transmission) total += weight(*t);
        EXPECT_NEAR(total, 1.0, 2e-6) << "ior " << n << " cos " << c << " side " << side;
      }
}

}  // namespace
}  // namespace prism
