// BSDF lobes: Fresnel identities, chi-square tests of sampling against pdfs, sample/eval/pdf
// agreement, energy bounds, reciprocity, and the laws of a smooth interface.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "chi_square.h"
#include "core/constants.h"
#include "core/pcg32.h"
#include "materials/bsdf.h"
#include "materials/conductor_bxdf.h"
#include "materials/dielectric_bxdf.h"
#include "materials/fresnel.h"
#include "materials/material_eval.h"
#include "materials/microfacet.h"
#include "statistics.h"

namespace prism {
namespace {

Vec3 direction(float theta_deg, float phi_deg = 30.0f) {
  const float t = theta_deg * kPi / 180.0f, p = phi_deg * kPi / 180.0f;
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

// --- Fresnel ---------------------------------------------------------------------------------

TEST(Fresnel, NormalIncidence) {
  for (float n : {1.0001f, 1.33f, 1.5f, 2.42f, 4.0f}) {
    const float expected = ((1 - n) / (1 + n)) * ((1 - n) / (1 + n));
    EXPECT_NEAR(fresnel_dielectric(1.0f, n), expected, 1e-6f) << n;
    EXPECT_NEAR(fresnel_dielectric(-1.0f, 1.0f / n), expected, 1e-6f) << n;  // same interface, other side
  }
}

TEST(Fresnel, BrewsterAngleHasNoParallelReflection) {
  for (float n : {1.33f, 1.5f, 2.42f}) {
    const float brewster = std::atan(n);
    const FresnelSP f = fresnel_dielectric_sp(std::cos(brewster), n);
    EXPECT_NEAR(f.p, 0.0f, 1e-6f) << n;
    EXPECT_GT(f.s, 0.01f) << n;
  }
}

TEST(Fresnel, TotalInternalReflectionBeyondTheCriticalAngle) {
  for (float n : {1.33f, 1.5f, 2.42f}) {
    const float critical = std::asin(1.0f / n);
    // From inside: cos_i < 0 in the outer frame, eta = n_back / n_front = n.
    EXPECT_EQ(fresnel_dielectric(-std::cos(critical + 1e-3f), n), 1.0f) << n;
    EXPECT_EQ(fresnel_dielectric(-std::cos(1.5f), n), 1.0f) << n;
    // Continuous into the critical angle: reflectance rises to 1 without jumps or NaN.
    float previous = 0;
    for (int i = 0; i <= 2000; ++i) {
      const float theta = critical * (0.9f + 0.1f * i / 2000.0f);
      const float r = fresnel_dielectric(-std::cos(theta), n);
      ASSERT_TRUE(std::isfinite(r));
      ASSERT_GE(r, previous - 1e-6f) << "not monotonic at " << theta;
      previous = r;
    }
    EXPECT_GT(previous, 0.99f);
  }
}

TEST(Fresnel, ReflectedPlusTransmittedIsOne) {
  // Transmittance from the independent amplitude coefficients (Hecht, Optics §4.6):
  // T = (n2 cos_t) / (n1 cos_i) t^2, with t_s = 2 n1 cos_i / (n1 cos_i + n2 cos_t),
  // t_p = 2 n1 cos_i / (n2 cos_i + n1 cos_t).
  for (float n : {1.0001f, 1.33f, 1.5f, 2.42f, 4.0f}) {
    for (float deg = 0; deg < 90.0f; deg += 0.7f) {
      const double ci = std::cos(deg * kPi / 180.0), si = std::sin(deg * kPi / 180.0);
      const double st = si / n, ct = std::sqrt(1 - st * st);
      const double ts = 2 * ci / (ci + n * ct), tp = 2 * ci / (n * ci + ct);
      const double Ts = n * ct / ci * ts * ts, Tp = n * ct / ci * tp * tp;
      const FresnelSP r = fresnel_dielectric_sp(float(ci), n);
      EXPECT_NEAR(r.s + Ts, 1.0, 2e-5) << n << " " << deg;
      EXPECT_NEAR(r.p + Tp, 1.0, 2e-5) << n << " " << deg;
    }
  }
}

TEST(Fresnel, IndexOneIsInvisibleAndGrazingIsFinite) {
  for (float deg = 0; deg <= 89.999f; deg += 0.5f) EXPECT_EQ(fresnel_dielectric(std::cos(deg * kPi / 180.0f), 1.0f), 0.0f);
  for (float n : {0.5f, 1.0001f, 1.5f, 4.0f})
    for (float c : {1e-7f, 1e-5f, 0.0f, -0.0f, -1e-7f}) {
      const float r = fresnel_dielectric(c, n);
      EXPECT_TRUE(std::isfinite(r) && r >= 0 && r <= 1) << n << " " << c;
    }
}

TEST(Fresnel, RefractionObeysSnell) {
  for (float n : {1.33f, 1.5f, 2.42f}) {
    const Vec3 wo = direction(40.0f);
    Vec3 wt;
    ASSERT_TRUE(refract(wo, Vec3(0, 0, 1), n, wt));
    EXPECT_NEAR(length(wt), 1.0f, 1e-5f);
    EXPECT_LT(wt.z, 0.0f);
    const float sin_i = std::sqrt(1 - wo.z * wo.z), sin_t = std::sqrt(1 - wt.z * wt.z);
    EXPECT_NEAR(sin_i, n * sin_t, 1e-5f);
    EXPECT_NEAR(std::atan2(wt.y, wt.x), std::atan2(-wo.y, -wo.x), 1e-5f);  // in the plane of incidence
    // Beyond the critical angle from inside, no refraction.
    EXPECT_FALSE(refract(Vec3(0.9f, 0, std::sqrt(1 - 0.81f)), Vec3(0, 0, 1), 1.0f / n, wt));
  }
}

// --- Sampling against pdfs -------------------------------------------------------------------

std::string check_dielectric(float eta, float alpha, DielectricBxdf::Mode mode, const Vec3& wo) {
  const DielectricBxdf b(eta, alpha, Rgb(1.0f), mode);
  return test::chi_square_sphere(
      [&](float ul, Vec2 u) -> std::optional<test::DirectionSample> {
        const auto s = b.sample(wo, ul, u);
        if (!s) return std::nullopt;
        return test::DirectionSample{s->wi, s->pdf};
      },
      [&](const Vec3& wi) { return b.pdf(wo, wi); });
}

TEST(ChiSquare, ConductorGgx) {
  for (float alpha : {0.1f, 0.3f, 1.0f})
    for (float deg : {0.0f, 45.0f, 80.0f, 89.0f}) {
      const ConductorBxdf b(Rgb(0.9f, 0.6f, 0.3f), alpha);
      const Vec3 wo = direction(deg);
      const std::string why = test::chi_square_sphere(
          [&](float, Vec2 u) -> std::optional<test::DirectionSample> {
            const auto s = b.sample(wo, u);
            if (!s) return std::nullopt;
            return test::DirectionSample{s->wi, s->pdf};
          },
          [&](const Vec3& wi) { return b.pdf(wo, wi); });
      EXPECT_EQ(why, "") << "alpha " << alpha << " theta " << deg;
    }
}

TEST(ChiSquare, RoughDielectricFromOutsideAndInside) {
  for (float eta : {1.5f, 2.42f, 1.0f / 1.33f})
    for (float alpha : {0.1f, 0.3f, 0.8f})
      for (float deg : {10.0f, 60.0f, 85.0f})
        for (float side : {1.0f, -1.0f}) {
          Vec3 wo = direction(deg);
          wo.z *= side;
          EXPECT_EQ(check_dielectric(eta, alpha, DielectricBxdf::Mode::Volume, wo), "")
              << "eta " << eta << " alpha " << alpha << " theta " << deg << " side " << side;
        }
}

TEST(ChiSquare, ThinWalledAndCoat) {
  for (float alpha : {0.1f, 0.5f})
    for (float deg : {20.0f, 80.0f}) {
      EXPECT_EQ(check_dielectric(1.5f, alpha, DielectricBxdf::Mode::ThinWalled, direction(deg)), "") << alpha << " " << deg;
      EXPECT_EQ(check_dielectric(1.5f, alpha, DielectricBxdf::Mode::ReflectionOnly, direction(deg)), "") << alpha << " " << deg;
    }
}

SurfaceParams material(float metallic, float roughness, float transmission, bool thin, float ior = 1.5f) {
  SurfaceParams p;
  p.base_color = Rgb(0.8f, 0.5f, 0.3f);
  p.metallic = metallic;
  p.roughness = roughness;
  p.transmission = transmission;
  p.thin_walled = thin;
  p.ior = ior;
  return p;
}

TEST(ChiSquare, GltfBsdfMixtures) {
  const SurfaceParams cases[] = {material(0, 1, 0, true, 1.0f),  // pure Lambertian
                                 material(0, 0.5f, 0, true),     // rough plastic
                                 material(0.5f, 0.4f, 0, true),  // half metal
                                 material(0, 0.4f, 0.5f, false), // half transmissive volume
                                 material(0, 0.6f, 1, true)};    // rough thin-walled sheet
  int index = 0;
  for (const SurfaceParams& p : cases) {
    for (float deg : {5.0f, 70.0f}) {
      const Vec3 wo = direction(deg);
      const Bsdf b(p, Vec3(0, 0, 1), Vec3(0, 0, 1), wo, p.ior);
      const std::string why = test::chi_square_sphere(
          [&](float ul, Vec2 u) -> std::optional<test::DirectionSample> {
            const auto s = b.sample(ul, u);
            if (!s) return std::nullopt;
            // Mixture samples report the mixture's f |cos| too.
            const Rgb e = b.eval(s->wi);
            if (std::abs(e.x - s->f_cos.x) > 1e-3f * std::max(e.x, s->f_cos.x) + 1e-6f) return std::nullopt;
            return test::DirectionSample{s->wi, s->pdf};
          },
          [&](const Vec3& wi) { return b.pdf(wi); });
      EXPECT_EQ(why, "") << "case " << index << " theta " << deg;
    }
    ++index;
  }
}

// --- Energy and reciprocity ------------------------------------------------------------------

// Directional albedo, in flux (refracted radiance scaling undone), estimated by sampling.
test::RunningStats albedo(const std::function<std::optional<BxdfSample>(float, Vec2)>& sample, const Vec3& wo) {
  Pcg32 rng(5, 9);
  test::RunningStats stats;
  for (int i = 0; i < 100000; ++i) {
    const auto s = sample(rng.next_float(), {rng.next_float(), rng.next_float()});
    if (!s) {
      stats.add(0);
      continue;
    }
    const float flux = s->transmission ? s->eta * s->eta : 1.0f;
    stats.add(double(max_component(s->f)) * std::abs(s->wi.z) / s->pdf * flux);
  }
  (void)wo;
  return stats;
}

TEST(Energy, NoLobeReflectsMoreThanItReceives) {
  for (float alpha : {0.0f, 0.05f, 0.3f, 1.0f})
    for (float deg : {0.0f, 30.0f, 60.0f, 85.0f, 89.9f}) {
      const Vec3 wo = direction(deg);
      const ConductorBxdf metal(Rgb(1.0f), alpha);
      const test::RunningStats m = albedo([&](float, Vec2 u) { return metal.sample(wo, u); }, wo);
      EXPECT_LE(m.mean(), 1.0 + test::kSigmas * m.standard_error() + 1e-6) << "metal " << alpha << " " << deg;
      for (float eta : {1.5f, 1.0f / 1.5f}) {
        for (auto mode : {DielectricBxdf::Mode::Volume, DielectricBxdf::Mode::ThinWalled, DielectricBxdf::Mode::ReflectionOnly}) {
          const DielectricBxdf d(eta, alpha, Rgb(1.0f), mode);
          const test::RunningStats a = albedo([&](float ul, Vec2 u) { return d.sample(wo, ul, u); }, wo);
          EXPECT_LE(a.mean(), 1.0 + test::kSigmas * a.standard_error() + 1e-6)
              << "dielectric eta " << eta << " alpha " << alpha << " theta " << deg << " mode " << int(mode);
        }
      }
    }
}

// Mean of f |cos| / pdf over BSDF samples: the directional albedo at wo.
test::RunningStats bsdf_albedo(const SurfaceParams& p, const Vec3& wo) {
  const Bsdf b(p, Vec3(0, 0, 1), Vec3(0, 0, 1), wo, p.ior);
  Pcg32 rng(3, 3);
  test::RunningStats stats;
  for (int i = 0; i < 100000; ++i) {
    const auto s = b.sample(rng.next_float(), {rng.next_float(), rng.next_float()});
    stats.add(s ? double(s->f_cos.x / s->pdf) : 0.0);
  }
  return stats;
}

TEST(Energy, WhitePlasticAndMetal) {
  for (float metallic : {0.0f, 1.0f})
    for (float deg : {0.0f, 60.0f, 88.0f}) {
      SurfaceParams p = material(metallic, 0.0f, 0, true);
      p.base_color = Rgb(1.0f);
      // Smooth: coat F plus (1 - F) x white diffuse, or a white mirror, reflects exactly everything.
      EXPECT_NEAR(bsdf_albedo(p, direction(deg)).mean(), 1.0, 1e-5) << metallic << " " << deg;
      // Rough: single-scattering microfacets lose energy (no multiple-scattering term), never gain it.
      for (float roughness : {0.3f, 1.0f}) {
        p.roughness = roughness;
        const test::RunningStats a = bsdf_albedo(p, direction(deg));
        EXPECT_LE(a.mean(), 1.0 + test::kSigmas * a.standard_error()) << metallic << " " << roughness << " " << deg;
      }
    }
  // GGX with alpha = 1 at normal incidence has the closed-form single-scattering albedo
  // 1 - ln 2 (D = 1/pi, G2 = 2 cos_i / (1 + cos_i), F = 1).
  SurfaceParams metal = material(1, 1, 0, true);
  metal.base_color = Rgb(1.0f);
  const test::RunningStats a = bsdf_albedo(metal, Vec3(0, 0, 1));
  EXPECT_NEAR(a.mean(), 1.0 - std::log(2.0), test::kSigmas * a.standard_error());
}

TEST(Reciprocity, ReflectionLobesAreSymmetric) {
  Pcg32 rng(8, 8);
  for (int i = 0; i < 2000; ++i) {
    Vec3 a = direction(89.0f * rng.next_float(), 360.0f * rng.next_float());
    Vec3 b = direction(89.0f * rng.next_float(), 360.0f * rng.next_float());
    for (float alpha : {0.1f, 0.6f}) {
      const ConductorBxdf m(Rgb(0.7f, 0.5f, 0.2f), alpha);
      const Rgb f1 = m.f(a, b), f2 = m.f(b, a);
      ASSERT_NEAR(f1.x, f2.x, 1e-4f * std::max(1.0f, f1.x));
      const DielectricBxdf d(1.5f, alpha, Rgb(1.0f), DielectricBxdf::Mode::Volume);
      ASSERT_NEAR(d.f(a, b).x, d.f(b, a).x, 1e-4f * std::max(1.0f, d.f(a, b).x));
    }
  }
}

// --- KHR_materials_specular ------------------------------------------------------------------

TEST(Specular, DefaultsLeaveTheExactFresnelAndColourTintsF0) {
  DielectricBxdf coat(1.5f, 0.0f, Rgb(1.0f), DielectricBxdf::Mode::ReflectionOnly);
  for (float c : {1.0f, 0.5f, 0.1f}) EXPECT_EQ(coat.reflectance_rgb(c), Rgb(coat.reflectance(c)));
  coat.set_specular(0.5f, Rgb(2.0f, 1.0f, 0.0f));
  const Rgb normal = coat.reflectance_rgb(1.0f);  // 0.5 x min(0.04 x colour, 1)
  EXPECT_NEAR(normal.x, 0.04f, 1e-6f);
  EXPECT_NEAR(normal.y, 0.02f, 1e-6f);
  EXPECT_NEAR(normal.z, 0.0f, 1e-6f);
  const Rgb grazing = coat.reflectance_rgb(1e-4f);  // grazing reflection stays white, x weight
  EXPECT_NEAR(grazing.x, 0.5f, 1e-3f);
  EXPECT_NEAR(grazing.z, 0.5f, 1e-3f);
}

TEST(Specular, ZeroSpecularLeavesPureDiffuseAndEnergyStaysBounded) {
  SurfaceParams p = material(0, 0.0f, 0, true);
  p.base_color = Rgb(1.0f);
  p.specular = 0;
  EXPECT_NEAR(bsdf_albedo(p, direction(30)).mean(), 1.0, 1e-5);  // all diffuse, no layer
  p.specular = 1;
  p.specular_color = Rgb(5.0f, 1.0f, 0.2f);  // F0 tints above 1 are capped
  for (float deg : {0.0f, 60.0f, 85.0f}) {
    const test::RunningStats a = bsdf_albedo(p, direction(deg));
    EXPECT_LE(a.mean(), 1.0 + test::kSigmas * a.standard_error()) << deg;
  }
}

TEST(Specular, OnGlassSamplingMatchesPdfAndEnergyIsBounded) {
  for (float alpha : {0.0f, 0.3f}) {
    DielectricBxdf glass(1.5f, alpha, Rgb(1.0f), DielectricBxdf::Mode::Volume);
    glass.set_specular(0.6f, Rgb(1.5f, 1.0f, 0.5f));
    const Vec3 wo = direction(35.0f);
    if (alpha > 0) {
      const std::string why = test::chi_square_sphere(
          [&](float ul, Vec2 u) -> std::optional<test::DirectionSample> {
            const auto s = glass.sample(wo, ul, u);
            if (!s) return std::nullopt;
            return test::DirectionSample{s->wi, s->pdf};
          },
          [&](const Vec3& wi) { return glass.pdf(wo, wi); });
      EXPECT_EQ(why, "");
    }
    const test::RunningStats a = albedo([&](float ul, Vec2 u) { return glass.sample(wo, ul, u); }, wo);
    EXPECT_LE(a.mean(), 1.0 + test::kSigmas * a.standard_error()) << alpha;
  }
  // Specular 0 removes the reflection: smooth glass transmits all of it.
  DielectricBxdf clear(1.5f, 0.0f, Rgb(1.0f), DielectricBxdf::Mode::Volume);
  clear.set_specular(0.0f, Rgb(1.0f));
  const auto s = clear.sample(direction(60.0f), 0.001f, {0.5f, 0.5f});
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->transmission);
  EXPECT_NEAR(s->pdf, 1.0f, 1e-6f);
}

// --- Robustness ------------------------------------------------------------------------------

TEST(Ggx, FiniteAtThePeakAndNormalisedForNarrowLobes) {
  // Regression: cos^2 (a^2 - 1) + 1 cancelled to 0 in float for a^2 below half an ulp of 1,
  // making D infinite at the mirror direction (seen as NaN samples on TransmissionTest).
  for (float alpha : {1.0001e-3f, 2e-3f, 0.01f, 0.2f, 1.0f}) {
    const GgxDistribution g(alpha);
    EXPECT_TRUE(std::isfinite(g.D(Vec3(0, 0, 1)))) << alpha;
    EXPECT_NEAR(g.D(Vec3(0, 0, 1)), 1.0 / (kPi * alpha * alpha), 1e-3 / (kPi * alpha * alpha)) << alpha;
    // Projected area: the integral of D(wm) cos(theta_m) over the hemisphere is 1. Integrate in
    // u = tan^2(theta) / alpha^2, where the lobe's width is 1 whatever alpha.
    double integral = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const double u0 = double(i) / n, u1 = double(i + 1) / n;
      const double x0 = u0 / (1 - u0 + 1e-300), x1 = u1 < 1 ? u1 / (1 - u1) : 1e300;  // map [0,1) to [0,inf)
      const double xm = 0.5 * (x0 + std::min(x1, x0 + 1e6));
      const double tan_t = alpha * std::sqrt(xm), c = 1 / std::sqrt(1 + tan_t * tan_t);
      const double s_ = tan_t * c;
      const double d_theta = alpha * 0.5 / std::sqrt(xm) * c * c * (std::min(x1, x0 + 1e6) - x0);
      integral += g.D(Vec3(float(s_), 0, float(c))) * c * s_ * 2 * kPi * d_theta;
    }
    EXPECT_NEAR(integral, 1.0, 2e-3) << alpha;
  }
}

TEST(Bsdf, EverySampleEvalAndPdfIsFinite) {
  Pcg32 rng(21, 22);
  const float etas[] = {1.0f, 1.0001f, 1.33f, 1.5f, 2.42f, 4.0f, 1.0f / 1.5f};
  const float roughnesses[] = {0.0f, 0.0316f, 0.0317f, 0.04f, 0.1f, 0.5f, 1.0f};
  for (int i = 0; i < 200000; ++i) {
    SurfaceParams p;
    p.base_color = Rgb(rng.next_float(), rng.next_float(), rng.next_float());
    p.metallic = rng.next_float() < 0.3f ? 1.0f : rng.next_float() * (rng.next_float() < 0.5f);
    p.roughness = roughnesses[rng.next_u32() % 7];
    p.transmission = rng.next_float() < 0.5f ? 0.0f : rng.next_float();
    p.thin_walled = rng.next_float() < 0.5f;
    const float eta = etas[rng.next_u32() % 7];
    const float theta = (rng.next_float() < 0.2f ? 1.5707f + 0.0001f * rng.next_float() : 3.1416f * rng.next_float());
    const float phi = kTwoPi * rng.next_float();
    const Vec3 wo(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    const Vec3 ns = normalize(Vec3(0.2f * (rng.next_float() - 0.5f), 0.2f * (rng.next_float() - 0.5f), 1.0f));
    const Bsdf b(p, ns, Vec3(0, 0, 1), wo, eta);
    const auto s = b.sample(rng.next_float(), {rng.next_float(), rng.next_float()});
    if (s) {
      ASSERT_TRUE(std::isfinite(s->pdf) && s->pdf > 0) << i;
      ASSERT_TRUE(is_finite(s->f_cos)) << i;
      ASSERT_TRUE(is_finite(s->wi) && std::abs(length(s->wi) - 1.0f) < 1e-3f) << i;
    }
    const Vec3 wi = normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
    ASSERT_TRUE(is_finite(b.eval(wi))) << i;
    ASSERT_TRUE(std::isfinite(b.pdf(wi))) << i;
  }
}

// --- Smooth interfaces -----------------------------------------------------------------------

TEST(SmoothDielectric, ChoosesReflectionWithFresnelProbabilityAndObeysSnell) {
  for (float eta : {1.33f, 1.5f, 2.42f})
    for (float deg : {0.0f, 30.0f, 70.0f, 89.0f}) {
      const Vec3 wo = direction(deg);
      const DielectricBxdf d(eta, 0.0f, Rgb(1.0f), DielectricBxdf::Mode::Volume);
      ASSERT_TRUE(d.is_delta());
      Pcg32 rng(1, 9);
      const int n = 40000;
      int reflected = 0;
      for (int i = 0; i < n; ++i) {
        const auto s = d.sample(wo, rng.next_float(), {rng.next_float(), rng.next_float()});
        ASSERT_TRUE(s);
        const float weight = s->f.x * std::abs(s->wi.z) / s->pdf;
        if (!s->transmission) {
          ++reflected;
          EXPECT_NEAR(weight, 1.0f, 1e-5f);
          EXPECT_NEAR(s->wi.z, wo.z, 1e-6f);
        } else {
          EXPECT_NEAR(weight, 1.0f / (eta * eta), 1e-5f);  // radiance scaling on entering
          const float sin_t = std::sqrt(std::max(0.0f, 1 - s->wi.z * s->wi.z));
          EXPECT_NEAR(std::sqrt(1 - wo.z * wo.z), eta * sin_t, 1e-5f);
        }
      }
      const double R = fresnel_dielectric(wo.z, eta);
      EXPECT_NEAR(double(reflected) / n, R, test::kSigmas * std::sqrt(R * (1 - R) / n) + 1e-9) << eta << " " << deg;
    }
}

TEST(SmoothDielectric, TotalInternalReflectionSendsEverythingBack) {
  const DielectricBxdf d(1.5f, 0.0f, Rgb(1.0f), DielectricBxdf::Mode::Volume);
  Vec3 wo = direction(60.0f);  // beyond asin(1/1.5) = 41.8 degrees
  wo.z = -wo.z;                // from inside
  Pcg32 rng(4, 4);
  for (int i = 0; i < 1000; ++i) {
    const auto s = d.sample(wo, rng.next_float(), {0.5f, 0.5f});
    ASSERT_TRUE(s);
    EXPECT_FALSE(s->transmission);
    EXPECT_NEAR(s->f.x * std::abs(s->wi.z) / s->pdf, 1.0f, 1e-6f);
  }
}

TEST(SmoothDielectric, IndexOneTransmitsEverythingUnbent) {
  const DielectricBxdf d(1.0f, 0.3f, Rgb(1.0f), DielectricBxdf::Mode::Volume);
  const Vec3 wo = direction(50.0f);
  const auto s = d.sample(wo, 0.3f, {0.2f, 0.7f});
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->transmission);
  EXPECT_EQ(s->wi, -wo);
  EXPECT_EQ(s->f.x * std::abs(s->wi.z) / s->pdf, 1.0f);
}

}  // namespace
}  // namespace prism

namespace prism {
namespace {

// lambertian_everywhere says what Bsdf::lambertian_only says of surface_params at any point, for
// materials whose factors decide it, and declines (nullopt) where a texture scales one of them.
TEST(LambertianEverywhere, AgreesWithTheParametersAtEveryPoint) {
  SceneDesc scene;
  ImageDesc& image = scene.images.emplace_back();
  image.width = image.height = 2;
  image.channels = 4;
  image.texels = {0, 0, 0, 0, 1, 1, 1, 1, 0.5f, 0.5f, 0.5f, 0.5f, 0, 1, 0, 1};
  scene.textures.push_back({.image = 0});
  const float nan = std::nanf("");
  const float metallics[] = {0, 1, -0.5f, 0.25f, nan}, transmissions[] = {0, 1, -1, 0.5f, nan};
  const float speculars[] = {1, 0, -1, 0.5f, nan}, etas[] = {1, 1.5f, 1 / 1.5f};
  Pcg32 rng(7, 8);
  int decided = 0, lambertian = 0, declined = 0;
  for (const float metallic : metallics)
    for (const float transmission : transmissions)
      for (const float specular : speculars)
        for (int textured = 0; textured < 4; ++textured)
          for (const float eta : etas) {
            MaterialDesc m;
            m.metallic = metallic;
            m.transmission = transmission;
            m.specular = specular;
            m.base_color_texture.texture = 0;  // does not decide it
            if (textured == 1) m.metallic_roughness_texture.texture = 0;
            if (textured == 2) m.transmission_texture.texture = 0;
            if (textured == 3) m.specular_texture.texture = 0;
            const std::optional<bool> said = lambertian_everywhere(m, eta);
            if (!said) {
              ++declined;
              EXPECT_NE(textured, 0);
              continue;
            }
            ++decided;
            lambertian += *said;
            for (int i = 0; i < 8; ++i) {
              const Vec2 uv{rng.next_float(), rng.next_float()};
              ASSERT_EQ(*said, Bsdf::lambertian_only(surface_params(scene, m, uv), eta))
                  << "metallic " << metallic << " transmission " << transmission << " specular " << specular
                  << " eta " << eta;
            }
          }
  EXPECT_EQ(declined, 3 * 5 * 5 * 5 * 3);
  EXPECT_GT(lambertian, 10);
  EXPECT_GT(decided - lambertian, 10);
}

}  // namespace
}  // namespace prism
