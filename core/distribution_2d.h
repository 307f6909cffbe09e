// Distribution2D: a piecewise-constant density over [0,1)^2 from a grid of weights, sampled by a
// marginal distribution over rows and a conditional one within the row (pbrt-v4 §A.5.6).
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "core/distribution_1d.h"
#include "core/vec3.h"

namespace prism {

// The column and row of the cell of a width x height grid over [0,1)^2 that holds p, clamped to
// the grid (an image's texels, a distribution's cells).
inline std::pair<int, int> grid_cell(Vec2 p, int width, int height) {
  return {std::clamp(static_cast<int>(p.x * float(width)), 0, width - 1),
          std::clamp(static_cast<int>(p.y * float(height)), 0, height - 1)};
}

class Distribution2D {
 public:
  Distribution2D() = default;
  // Row by row, without the whole grid of weights in memory: row_weights(y, row) fills row y's
  // `width` weights (rows run along v, columns along u). Rows are built in parallel (row_weights must allow that), each alone, so the result
  // does not depend on the thread count.
  Distribution2D(int width, int height, const std::function<void(int y, std::vector<double>& row)>& row_weights);

  // Bytes a width x height distribution takes: each row's CDF in floats, its guide, and the marginal.
  static uint64_t footprint(int width, int height);

  bool empty() const { return marginal_.size() == 0; }
  // The sum of the positive weights.
  double total() const { return marginal_.total(); }

  // A point in [0,1)^2 and its density with respect to area in [0,1)^2.
  Vec2 sample(Vec2 u, float& pdf) const {
    Vec2 p;
    sample(&u, 1, &p, &pdf);
    return p;
  }
  // sample() for each of the n draws u[i], into p[i] and pdf[i]. The draws go together, stage by
  // stage, each stage asking the cache for what the next one reads (a row's guide, then its CDF),
  // so that on a large map the draws' misses overlap instead of following one another.
  void sample(const Vec2* u, int n, Vec2* p, float* pdf) const;

  float pdf(Vec2 p) const {
    const auto [x, y] = cell(p);
    const float row_pmf = marginal_.pmf(y);
    if (!(row_pmf > 0)) return 0;  // a row of no weight has no CDF to read
    return float(double(row_pmf) * row_cdf(y).pmf(x) * double(width_) * height_);
  }

  // Asks the cache for the CDF entries pdf(p) will read.
  void prefetch(Vec2 p) const {
    const auto [x, y] = cell(p);
    if (!cdfs_.empty()) __builtin_prefetch(&cdfs_[y * (size_t(width_) + 1) + x]);
  }

 private:
  // The column and row of the cell holding p.
  std::pair<size_t, size_t> cell(Vec2 p) const {
    const auto [x, y] = grid_cell(p, width_, height_);
    return {size_t(x), size_t(y)};
  }

  // A row's CDF is in floats: half the memory of doubles (an 8K map's rows take 128 MiB, not 256),
  // and twice the entries per cache line for the search, which waits on memory. The marginal over
  // the rows stays in doubles (it is small). See GuidedCdf for what floats change: nothing in the
  // expected image.
  using RowCdf = GuidedCdf<float>;
  RowCdf row_cdf(size_t y) const {
    return {cdfs_.data() + y * (size_t(width_) + 1), guides_.data() + y * (slots_ + 1), size_t(width_), slots_};
  }

  int width_ = 0, height_ = 0;
  size_t slots_ = 0;  // guide slots per row
  // Every row's CDF, and then every row's guide, one after another in one buffer each (a large
  // map's can then sit on huge pages).
  std::vector<float> cdfs_;
  std::vector<uint32_t> guides_;
  Distribution1D marginal_;
};

}  // namespace prism
