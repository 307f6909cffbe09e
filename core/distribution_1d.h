// Distribution1D: a discrete distribution over N items proportional to given weights.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace prism {

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
    if (remapped) {
      const double width = cdf_[i + 1] - cdf_[i];
      const double r = width > 0 ? (u - cdf_[i]) / width : 0.0;
      *remapped = static_cast<float>(std::clamp(r, 0.0, static_cast<double>(0x1.fffffep-1f)));
    }
    return i;
  }

 private:
  std::vector<double> cdf_;
  double total_ = 0;
};

}  // namespace prism
