#include "core/stratified_error.h"

#include <algorithm>
#include <cmath>

namespace prism {
namespace {

// Sums of `v` (a width x height grid) over the 2r+1 values around each along one axis, x or y,
// clipped at the grid's edges.
std::vector<double> sums_along(const std::vector<double>& v, int width, int height, bool along_y, int r) {
  std::vector<double> out(v.size());
  const int length = along_y ? height : width;
  const size_t step = along_y ? size_t(width) : 1;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int at = along_y ? y : x;
      const size_t i = size_t(y) * size_t(width) + size_t(x), line_start = i - size_t(at) * step;
      double s = 0;
      for (int k = std::max(0, at - r); k <= std::min(length - 1, at + r); ++k) s += v[line_start + size_t(k) * step];
      out[i] = s;
    }
  return out;
}

// Sums of `v` over the (2r+1)^2 window around each pixel, clipped to the image (separable).
std::vector<double> window_sums(const std::vector<double>& v, int width, int height, int r) {
  return sums_along(sums_along(v, width, height, false, r), width, height, true, r);
}

}  // namespace

// A pixel whose film recorded its luminance sums at m and 2m samples has two means, A over samples
// [0, m) and B over [m, 2m). Were the samples independent with per-sample luminance variance s^2,
// D = B - A would have E[D^2] = 2 s^2 / m. With Owen-scrambled Sobol points each of the two
// aligned blocks is a scrambled net of its own (their union a finer one, so their errors are, if
// anything, anti-correlated and E[D^2] only grows), and E[D^2] / (2 s^2 / m) measures how far the
// sampler's variance at m samples lies below the independent one. Stratified error falls faster
// than 1 / n, so at the pixel's n >= 2m the true factor is lower still: the estimate errs on the
// side of more samples. One pixel's D^2 is a single chi-square draw, so the factor is the ratio of
// the sums of D^2 and of 2 s^2 / m over a window (81 pixels: about +-16% on a smooth image).
// s is the luminance of the channels' standard deviations, the bound SampleSchedule's relative
// error uses, so the bound cancels when the factor scales that error.
std::vector<double> stratification_factors(const Film& film) {
  const int width = film.width(), height = film.height();
  const size_t pixels = size_t(width) * size_t(height);
  std::vector<double> d2(pixels, 0.0), expected(pixels, 0.0);
  if (film.tracks_halves())
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const Film::Halves& h = film.halves(x, y);
        const uint64_t n = film.sample_count(x, y);
        if (!h.valid() || n < 2) continue;
        const double m = double(h.lower_count);
        const Rgb v = film.variance_of_mean(x, y);
        const double s = luminance(Rgb(std::sqrt(v.x), std::sqrt(v.y), std::sqrt(v.z))) * std::sqrt(double(n));
        const double d = (h.upper - 2 * h.lower) / m;
        const size_t i = size_t(y) * size_t(width) + size_t(x);
        d2[i] = d * d;
        expected[i] = 2 * s * s / m;
      }
  const std::vector<double> d2_sums = window_sums(d2, width, height, kStratificationRadius);
  const std::vector<double> expected_sums = window_sums(expected, width, height, kStratificationRadius);
  std::vector<double> factors(pixels, 1.0);
  for (size_t i = 0; i < pixels; ++i) {
    const double ratio = d2_sums[i] / expected_sums[i];
    // No evidence (0 / 0), or radiance near float's limit (inf / inf): the independent estimate.
    if (expected_sums[i] > 0 && std::isfinite(ratio)) factors[i] = std::clamp(ratio, kMinStratificationFactor, 1.0);
  }
  return factors;
}

}  // namespace prism
