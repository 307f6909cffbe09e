#include "core/error_allocation.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/image_metrics.h"
#include "core/pixel_neighbours.h"

namespace prism {

std::vector<double> error_weights(const Film& film) {
  const int width = film.width(), height = film.height();
  const size_t pixels = size_t(width) * size_t(height);
  // R of every pixel from its own samples first; a pixel's weight then averages its neighbours'.
  std::vector<double> r(pixels, 0.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const uint64_t n = film.sample_count(x, y);
      if (n < 2) continue;
      const Rgb variance_of_mean = film.variance_of_mean(x, y);
      float m[4];
      film.mean(x, y, m);
      double sum = 0;
      for (int c = 0; c < 3; ++c)
        sum += double(variance_of_mean[c]) * double(n) / (double(m[c]) * m[c] + kRelMseEpsilon);
      r[size_t(y) * width + x] = std::isfinite(sum) ? sum : 0.0;
    }
  return neighbour_weights(r, width, height);
}

std::vector<double> neighbour_weights(const std::vector<double>& r, int width, int height) {
  const size_t pixels = size_t(width) * size_t(height);
  std::vector<double> weights(pixels, 0.0);
  bool any = false;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double sum = 0;
      int neighbours = 0;
      for_each_neighbour(x, y, width, height, [&](int nx, int ny) {
        sum += r[size_t(ny) * width + nx];
        ++neighbours;
      });
      const double w = neighbours > 0 ? std::sqrt(sum / neighbours) : 0.0;
      weights[size_t(y) * width + x] = w;
      any = any || w > 0;
    }
  if (!any) std::fill(weights.begin(), weights.end(), 1.0);
  return weights;
}

uint64_t allocate_samples(const std::vector<uint32_t>& counts, const std::vector<double>& weights, uint64_t total,
                          uint32_t cap, std::vector<uint32_t>& target) {
  const size_t pixels = counts.size();
  target.resize(pixels);
  // A pixel's real-valued share at level lambda: lambda x weight, at least its count, at most cap.
  auto share = [&](size_t i, double lambda) {
    const double lo = counts[i], hi = std::max<double>(cap, counts[i]);
    return std::clamp(lambda * weights[i], lo, hi);
  };
  auto sum_at = [&](double lambda) {
    double sum = 0;
    for (size_t i = 0; i < pixels; ++i) sum += share(i, lambda);
    return sum;
  };
  // The sum grows with lambda; bisect for the level whose shares add up to `total`.
  double lo = 0, hi = 1;
  while (sum_at(hi) < double(total) && hi < 1e300) hi *= 2;
  for (int iteration = 0; iteration < 200 && hi > lo * (1 + 1e-15); ++iteration) {
    const double mid = 0.5 * (lo + hi);
    if (sum_at(mid) < double(total)) lo = mid;
    else hi = mid;
  }
  // Whole samples: each pixel's share rounded down, then the samples left over, one each, to the
  // pixels with the largest remainders (lower index first on ties) until the total is reached.
  uint64_t sum = 0;
  std::vector<std::pair<double, size_t>> remainders;
  remainders.reserve(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    const double s = share(i, hi);
    target[i] = uint32_t(std::floor(s));
    sum += target[i];
    if (target[i] < std::max(cap, counts[i])) remainders.emplace_back(s - std::floor(s), i);
  }
  if (sum < total) {
    const size_t extra = size_t(std::min<uint64_t>(total - sum, remainders.size()));
    std::partial_sort(remainders.begin(), remainders.begin() + extra, remainders.end(),
                      [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
    for (size_t k = 0; k < extra; ++k) ++target[remainders[k].second];
    sum += extra;
  }
  return sum;
}

}  // namespace prism
