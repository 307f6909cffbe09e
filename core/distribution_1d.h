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

// A normalised CDF over `items` items and its guide table, held by whoever built them: what
// sampling reads. The item drawn for u is the last i with cdf[i] <= u (so cdf[i] <= u < cdf[i+1],
// and item i has weight > 0). guide[g] is the last i with cdf[i] <= g / slots, for slots + 1 evenly
// spaced values: a draw in [g, g + 1) / slots falls on an item between guide[g] and guide[g + 1]
// (the guide table of Chen and Asau 1974, ahead of a binary search). About one slot per four items,
// so that the table adds an eighth to the CDF's memory and the search takes two or three steps.
// Below 16 items there is no guide (slots 0): the search over the whole CDF is as short, and
// reading a guide cost a light pick among a few lights 7 ns in 37.
// Entry is double or float. In floats, an item whose weight is below the float spacing of the CDF
// around it gets an interval of width 0: it is never drawn and its pmf is 0, consistently, so an
// estimator that weighs the draws by pmf (or MIS with another strategy) stays unbiased.
template <typename Entry>
struct GuidedCdf {
  const Entry* cdf = nullptr;       // items + 1 entries, from 0 to 1
  const uint32_t* guide = nullptr;  // slots + 1 entries
  size_t items = 0, slots = 0;

  static size_t slots_for(size_t items) { return items < 16 ? 0 : std::bit_floor(items) / 4; }
  // Writes the items + 1 entries of cdf from the weights (negative and non-finite ones count as
  // zero) and returns their total; when that is 0 nothing is written and there is nothing to sample.
  // The running sums are in doubles whatever Entry is; each is divided by the total once.
  static double build_cdf(const double* weights, size_t items, Entry* cdf) {
    const auto weight = [&](size_t i) { return weights[i] > 0 && weights[i] < 1e300 ? weights[i] : 0.0; };
    double total = 0;
    for (size_t i = 0; i < items; ++i) total += weight(i);
    if (!(total > 0)) return 0;
    double running = 0;
    cdf[0] = 0;
    for (size_t i = 0; i < items; ++i) {
      running += weight(i);
      cdf[i + 1] = static_cast<Entry>(running / total);
    }
    cdf[items] = 1;
    return total;
  }
  static void build_guide(const Entry* cdf, size_t items, uint32_t* guide, size_t slots) {
    if (slots == 0) return;
    size_t i = 0;
    for (size_t g = 0; g <= slots; ++g) {
      const double value = double(g) / double(slots);
      while (i < items && cdf[i + 1] <= value) ++i;
      guide[g] = static_cast<uint32_t>(i);
    }
  }

  float pmf(size_t i) const { return i < items ? static_cast<float>(double(cdf[i + 1]) - double(cdf[i])) : 0.0f; }

  // The CDF entries [first, first + len) the search for u stays within: between the guide's two
  // entries around u, or the whole CDF without a guide.
  struct Bracket {
    size_t first = 0, len = 0;
  };
  // The guide entry bracket(u) reads first (the next is beside it), for asking the cache ahead.
  const uint32_t* guide_entry(float u) const {
    const double x = u;
    // x * slots is exact (slots is a power of two); the guide brackets the answer.
    return guide + (x > 0 ? std::min(static_cast<size_t>(x * double(slots)), slots - 1) : 0);
  }
  Bracket bracket(float u) const {
    if (slots == 0) return {0, items + 1};
    const uint32_t* g = guide_entry(u);
    return {g[0], size_t(g[1] - g[0]) + 1};
  }
  // The item for u in [0, 1), by a binary search within b = bracket(u); u is rescaled to [0, 1)
  // within the item's interval so one sample dimension can be reused.
  size_t search(Bracket b, float u, float* remapped) const {
    const double x = u;
    const Entry* base = cdf + b.first;
    for (size_t len = b.len; len > 1;) {
      const size_t half = len / 2;
      base = base[half] <= x ? base + half : base;
      len -= half;
    }
    const size_t i = std::min(static_cast<size_t>(base - cdf), items - 1);
    if (remapped) *remapped = rescale_to_unit(u, cdf[i], double(cdf[i + 1]) - double(cdf[i]));
    return i;
  }
  size_t sample(float u, float* remapped) const { return search(bracket(u), u, remapped); }
};

class Distribution1D {
 public:
  Distribution1D() = default;
  // Negative and non-finite weights count as zero. With all weights zero the
  // distribution is empty (size() == 0 after construction means nothing to sample).
  explicit Distribution1D(const std::vector<double>& weights) {
    cdf_.resize(weights.size() + 1);
    total_ = GuidedCdf<double>::build_cdf(weights.data(), weights.size(), cdf_.data());
    if (!(total_ > 0)) {
      cdf_.clear();
      return;
    }
    if (const size_t slots = GuidedCdf<double>::slots_for(weights.size()); slots > 0) {
      guide_.resize(slots + 1);
      GuidedCdf<double>::build_guide(cdf_.data(), weights.size(), guide_.data(), slots);
    }
  }

  size_t size() const { return cdf_.empty() ? 0 : cdf_.size() - 1; }
  double total() const { return total_; }
  // 0 past the end, and for every item of an empty distribution (all weights zero).
  float pmf(size_t i) const { return view().pmf(i); }
  // The weight of the items before item i, over the total: 0 for i = 0, 1 for i = size().
  double cdf(size_t i) const { return cdf_[i]; }

  // Picks an item for u in [0,1) (the distribution must not be empty); returns its index and
  // rescales u to [0,1) within the item's interval so one sample dimension can be reused.
  size_t sample(float u, float* remapped = nullptr) const { return view().sample(u, remapped); }

 private:
  GuidedCdf<double> view() const { return {cdf_.data(), guide_.data(), size(), guide_.empty() ? 0 : guide_.size() - 1}; }

  std::vector<double> cdf_;
  std::vector<uint32_t> guide_;
  double total_ = 0;
};

}  // namespace prism
