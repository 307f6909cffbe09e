#include "core/distribution_2d.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace prism {

Distribution2D::Distribution2D(int width, int height,
                               const std::function<void(int y, std::vector<double>& row)>& row_weights)
    : width_(width), height_(height), rows_(size_t(std::max(height, 0))) {
  std::vector<double> row_sums(rows_.size(), 0.0);
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& range) {
    std::vector<double> row(size_t(std::max(width, 0)));
    for (int y = range.begin(); y != range.end(); ++y) {
      row_weights(y, row);
      for (double w : row) row_sums[size_t(y)] += w > 0 ? w : 0.0;
      rows_[size_t(y)] = Distribution1D(row);
    }
  });
  marginal_ = Distribution1D(row_sums);
}

uint64_t Distribution2D::footprint(int width, int height) {
  const uint64_t cdf = (uint64_t(width) + 1) * sizeof(double), guide = (uint64_t(width) / 4 + 2) * sizeof(uint32_t);
  return uint64_t(height) * (cdf + guide + sizeof(Distribution1D)) + (uint64_t(height) + 1) * sizeof(double);
}

}  // namespace prism
