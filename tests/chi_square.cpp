#include "chi_square.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "core/constants.h"
#include "core/pcg32.h"

namespace prism::test {

double chi2(const std::vector<double>& observed, const std::vector<double>& expected) {
  double x = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    const double d = observed[i] - expected[i];
    x += d * d / expected[i];
  }
  return x;
}

double chi2_critical(int dof) {
  const double z = 4.265, k = dof;
  const double t = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
  return k * t * t * t;
}

std::string chi_square_sphere(const std::function<std::optional<DirectionSample>(float, Vec2)>& sample,
                              const std::function<float(const Vec3&)>& pdf, int samples) {
  constexpr int kTheta = 64, kPhi = 128, kSub = 8;
  std::vector<double> observed(kTheta * kPhi, 0.0), expected(kTheta * kPhi, 0.0);
  auto bin_of = [&](const Vec3& w) {
    const double theta = std::acos(std::clamp(double(w.z), -1.0, 1.0));
    double phi = std::atan2(double(w.y), double(w.x));
    if (phi < 0) phi += 2.0 * kPi;
    const int t = std::min(kTheta - 1, static_cast<int>(theta / kPi * kTheta));
    const int p = std::min(kPhi - 1, static_cast<int>(phi / (2.0 * kPi) * kPhi));
    return t * kPhi + p;
  };
  Pcg32 rng(17, 23);
  double failures = 0;
  int mismatches = 0;
  std::ostringstream why;
  for (int i = 0; i < samples; ++i) {
    const float ul = rng.next_float();
    const Vec2 u{rng.next_float(), rng.next_float()};
    const auto s = sample(ul, u);
    if (!s) {
      failures += 1;
      continue;
    }
    const float p = pdf(s->wi);
    if (std::abs(p - s->pdf) > 1e-3f * std::max(p, s->pdf) + 1e-5f && mismatches++ == 0)
      why << "sample pdf " << s->pdf << " differs from pdf(wi) " << p << "; ";
    observed[bin_of(s->wi)] += 1;
  }
  // Midpoint rule in (theta, phi) with the sin(theta) Jacobian, refined where it has not
  // converged: rough refraction has sharp ridges that a coarse rule overshoots.
  const double dt = kPi / kTheta, dp = 2.0 * kPi / kPhi;
  auto integrate = [&](int t, int p, int sub) {
    double sum = 0;
    for (int a = 0; a < sub; ++a)
      for (int b = 0; b < sub; ++b) {
        const double theta = (t + (a + 0.5) / sub) * dt, phi = (p + (b + 0.5) / sub) * dp;
        const Vec3 w(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                     float(std::cos(theta)));
        sum += pdf(w) * std::sin(theta);
      }
    return sum * dt * dp / (sub * sub) * samples;
  };
  double total = 0;
  for (int t = 0; t < kTheta; ++t)
    for (int p = 0; p < kPhi; ++p) {
      double coarse = integrate(t, p, kSub);
      for (int sub = 2 * kSub; sub <= 16 * kSub; sub *= 2) {
        const double fine = integrate(t, p, sub);
        const bool converged = std::abs(fine - coarse) <= 1e-3 * fine + 0.05;
        coarse = fine;
        if (converged) break;
      }
      expected[t * kPhi + p] = coarse;
      total += coarse;
    }
  // Pool sparse bins; the mass the pdf does not cover is the expected failure count.
  double chi2 = 0, pooled_o = 0, pooled_e = 0;
  int dof = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < 5) {
      pooled_o += observed[i];
      pooled_e += expected[i];
    } else {
      chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
      ++dof;
    }
  }
  pooled_o += failures;
  pooled_e += std::max(0.0, samples - total);
  if (pooled_e >= 5) {
    chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
    ++dof;
  } else if (pooled_o > 20) {
    why << pooled_o << " samples where the pdf expects " << pooled_e << "; ";
  }
  if (std::getenv("PRISM_CHI2_DEBUG") && dof > 1 && chi2 > chi2_critical(dof - 1)) {
    std::vector<std::pair<double, int>> worst;
    for (size_t i = 0; i < observed.size(); ++i)
      if (expected[i] >= 5) worst.push_back({(observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i], int(i)});
    std::sort(worst.rbegin(), worst.rend());
    for (int k = 0; k < 6 && k < int(worst.size()); ++k)
      why << "[theta bin " << worst[k].second / kPhi << " phi bin " << worst[k].second % kPhi << ": obs "
          << observed[worst[k].second] << " exp " << expected[worst[k].second] << "] ";
    why << "failures " << failures << " vs " << samples - total << "; ";
  }
  if (dof > 1 && chi2 > chi2_critical(dof - 1)) why << "chi2 " << chi2 << " > " << chi2_critical(dof - 1) << " (dof " << dof - 1 << "); ";
  if (mismatches) why << mismatches << " pdf mismatches; ";
  return why.str();
}

}  // namespace prism::test
