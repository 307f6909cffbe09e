#include "core/distribution_2d.h"

#include "core/huge_pages.h"
#include "core/parallel_ranges.h"

namespace prism {

Distribution2D::Distribution2D(int width, int height,
                               const std::function<void(int y, std::vector<double>& row)>& row_weights)
    : width_(std::max(width, 0)), height_(std::max(height, 0)), slots_(RowCdf::slots_for(size_t(width_))) {
  resize_on_huge_pages(cdfs_, size_t(height_) * (size_t(width_) + 1));
  resize_on_huge_pages(guides_, size_t(height_) * (slots_ + 1));
  std::vector<double> row_sums(size_t(height_), 0.0);
  parallel_ranges(height_, 0, [&](int first, int end) {
    std::vector<double> row(static_cast<size_t>(width_));
    for (int y = first; y != end; ++y) {
      row_weights(y, row);
      for (double w : row) row_sums[size_t(y)] += w > 0 ? w : 0.0;
      float* cdf = cdfs_.data() + size_t(y) * (size_t(width_) + 1);
      // A row of no weight is never drawn (its marginal probability is 0): it needs no guide.
      if (RowCdf::build_cdf(row.data(), row.size(), cdf) > 0)
        RowCdf::build_guide(cdf, row.size(), guides_.data() + size_t(y) * (slots_ + 1), slots_);
    }
  });
  marginal_ = Distribution1D(row_sums);
}

void Distribution2D::sample(const Vec2* u, int n, Vec2* p, float* pdf) const {
  constexpr int kBatch = 8;
  for (int first = 0; first < n; first += kBatch) {
    const int m = std::min(n - first, kBatch);
    const Vec2* uu = u + first;
    size_t y[kBatch];
    float ry[kBatch];
    // The marginal (a few KiB, in cache) picks each row; its guide entry is asked for.
    for (int i = 0; i < m; ++i) {
      y[i] = marginal_.sample(uu[i].y, &ry[i]);
      if (slots_ > 0) __builtin_prefetch(row_cdf(y[i]).guide_entry(uu[i].x));
    }
    // The guide brackets the search; the CDF entries where it starts are asked for.
    RowCdf::Bracket bracket[kBatch];
    for (int i = 0; i < m; ++i) {
      const RowCdf row = row_cdf(y[i]);
      bracket[i] = row.bracket(uu[i].x);
      __builtin_prefetch(row.cdf + bracket[i].first);
      __builtin_prefetch(row.cdf + bracket[i].first + bracket[i].len - 1);
    }
    for (int i = 0; i < m; ++i) {
      const RowCdf row = row_cdf(y[i]);
      float rx = 0;
      const size_t x = row.search(bracket[i], uu[i].x, &rx);
      pdf[first + i] = float(double(marginal_.pmf(y[i])) * row.pmf(x) * double(width_) * height_);
      p[first + i] = {(float(x) + rx) / float(width_), (float(y[i]) + ry[i]) / float(height_)};
    }
  }
}

uint64_t Distribution2D::footprint(int width, int height) {
  const uint64_t cdf = (uint64_t(width) + 1) * sizeof(float);
  const uint64_t guide = (RowCdf::slots_for(size_t(std::max(width, 0))) + 1) * sizeof(uint32_t);
  return uint64_t(height) * (cdf + guide) + (uint64_t(height) + 1) * sizeof(double);
}

}  // namespace prism
