// Distribution1D: a discrete distribution over N items proportional to given weights.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
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
    build_guide();
  }

  size_t size() const { return cdf_.empty() ? 0 : cdf_.size() - 1; }
  double total() const { return total_; }
  // 0 past the end, and for every item of an empty distribution (all weights zero).
  float pmf(size_t i) const { return i < size() ? static_cast<float>(cdf_[i + 1] - cdf_[i]) : 0.0f; }
  // The weight of the items before item i, over the total: 0 for i = 0, 1 for i = size().
  double cdf(size_t i) const { return cdf_[i]; }

  // Picks an item for u in [0,1) (the distribution must not be empty); returns its index and rescales u to [0,1) within the
  // item's interval so one sample dimension can be reused.
  // The item is the last i with cdf[i] <= u (so cdf[i] <= u < cdf[i+1], and item i has weight > 0),
  // found by a binary search between the guide's two entries around u.
  size_t sample(float u, float* remapped = nullptr) const {
    const double x = u;
    const size_t slots = guide_.size() - 1;
    // x * slots is exact (slots is a power of two); the guide brackets the answer.
    const size_t slot = x > 0 ? std::min(static_cast<size_t>(x * double(slots)), slots - 1) : 0;
    const double* base = cdf_.data() + guide_[slot];
    for (size_t len = guide_[slot + 1] - guide_[slot] + 1; len > 1;) {
      const size_t half = len / 2;
      base = base[half] <= x ? base + half : base;
      len -= half;
    }
    const size_t i = std::min(static_cast<size_t>(base - cdf_.data()), size() - 1);
    if (remapped) *remapped = rescale_to_unit(u, cdf_[i], cdf_[i + 1] - cdf_[i]);
    return i;
  }

 private:
  // guide_[g] is the last i with cdf[i] <= g / slots, for slots + 1 evenly spaced values g / slots:
  // a draw in [g, g + 1) / slots falls on an item between guide_[g] and guide_[g + 1] (the guide
  // table of Chen and Asau 1974, ahead of a binary search). About one slot per four items, so that
  // the table adds an eighth to the CDF's memory and the search takes two or three steps.
  void build_guide() {
    const size_t slots = std::max<size_t>(1, std::bit_floor(size()) / 4);
    guide_.resize(slots + 1);
    size_t i = 0;
    for (size_t g = 0; g <= slots; ++g) {
      const double value = double(g) / double(slots);
      while (i + 1 < cdf_.size() && cdf_[i + 1] <= value) ++i;
      guide_[g] = static_cast<uint32_t>(i);
    }
  }

  std::vector<double> cdf_;
  std::vector<uint32_t> guide_;
  double total_ = 0;
};

}  // namespace prism
