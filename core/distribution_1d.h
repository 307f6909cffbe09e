// Distribution1D: a discrete distribution over N items proportional to given weights.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/constants.h"

namespace prism {

// u in [start, start + width) rescaled to [0, 1), so that one sample dimension can be reused after
// it has chosen the interval; 0 for an empty interval.
inline float rescale_to_unit(float u, double start, double width) {
  const double r = width > 0 ? (u - start) / width : 0.0;
  return static_cast<float>(std::clamp(r, 0.0, static_cast<double>(kOneMinusEpsilon)));
}

class Distribution1D {
 public:
  Distribution1D() = default;
  // Negative and non-finite weights count as zero. With all weights zero the
  // distribution is empty (size() == 0 after construction means nothing to sample).
  explicit Distribution1D(const std::vector<double>& weights) {
    cdf_.resize(weights.size() + 1, 0.0);
    for (size_t i = 0; i < weights.size(); ++i) {
      const double w = weights[i] > 0 && weights[i] < 1e300 ? weights[i] : 0.0;
      cdf_[i + 1] = cdf_[i] + w;
    }
    total_ = cdf_.back();
    if (total_ <= 0) {
      cdf_.clear();
      return;
    }
    for (double& c : cdf_) c /= total_;
    cdf_.back() = 1.0;
  }

  size_t size() const { return cdf_.empty() ? 0 : cdf_.size() - 1; }
  double total() const { return total_; }
  // 0 past the end, and for every item of an empty distribution (all weights zero).
  float pmf(size_t i) const { return i < size() ? static_cast<float>(cdf_[i + 1] - cdf_[i]) : 0.0f; }

  // Picks an item for u in [0,1); returns its index and rescales u to [0,1) within the
  // item's interval so one sample dimension can be reused.
  size_t sample(float u, float* remapped = nullptr) const {
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), static_cast<double>(u));
    size_t i = static_cast<size_t>(std::max<std::ptrdiff_t>(0, (it - cdf_.begin()) - 1));
    i = std::min(i, size() - 1);  // cdf[i] <= u < cdf[i+1], so item i has weight > 0
    if (remapped) *remapped = rescale_to_unit(u, cdf_[i], cdf_[i + 1] - cdf_[i]);
    return i;
  }

 private:
  std::vector<double> cdf_;
  double total_ = 0;
};

}  // namespace prism
