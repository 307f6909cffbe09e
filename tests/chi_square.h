// Chi-square goodness-of-fit of a direction sampler against its pdf over the whole sphere.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace prism::test {

struct DirectionSample {
  Vec3 wi;
  float pdf;
};

// Draws `samples` directions (a failed draw returns nullopt and counts as "no direction"), bins
// them on a theta x phi grid, integrates `pdf` over each bin numerically, pools bins expecting
// fewer than 5, and returns a message describing the failure, or "" when the statistic is under
// the 1e-5 significance critical value. Also checks that each sample's pdf matches pdf(wi).
std::string chi_square_sphere(const std::function<std::optional<DirectionSample>(float, Vec2)>& sample,
                              const std::function<float(const Vec3&)>& pdf, int samples = 400000);

// Pearson's statistic of counts observed in bins against those expected.
double chi2(const std::vector<double>& observed, const std::vector<double>& expected);

// Chi-square critical value at significance 1e-5 (Wilson-Hilferty approximation).
double chi2_critical(int dof);

}  // namespace prism::test
