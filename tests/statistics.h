// Running mean and variance (Welford) for statistical tests, with the standard error of the mean.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace prism::test {

class RunningStats {
 public:
  void add(double x) {
    ++n_;
    const double d = x - mean_;
    mean_ += d / double(n_);
    m2_ += d * (x - mean_);
  }
  uint64_t count() const { return n_; }
  double mean() const { return mean_; }
  double variance() const { return n_ > 1 ? m2_ / double(n_ - 1) : 0.0; }
  double standard_error() const { return n_ > 0 ? std::sqrt(variance() / double(n_)) : 0.0; }

 private:
  uint64_t n_ = 0;
  double mean_ = 0, m2_ = 0;
};

// Do two methods A and B render the same image? Given two renders by each with different seeds,
// a0, a1 and b0, b1 value by value, differences across methods (a0 - b1, a1 - b0) must be no larger
// than differences across seeds (a0 - a1, b0 - b1). The ratio of their summed squares is judged by
// its own spread: the delta method over the per-value terms gives the variance of its logarithm,
// so a few very noisy pixels (edges, caustics) widen the band as much as they should and no more.
class SeedSwapTest {
 public:
  void add(double a0, double a1, double b0, double b1) {
    const double s = sq(a0 - b1) + sq(a1 - b0), n = sq(a0 - a1) + sq(b0 - b1);
    ++count_;
    s_ += s;
    n_ += n;
    ss_ += s * s;
    nn_ += n * n;
    sn_ += s * n;
  }
  double ratio() const { return s_ / n_; }
  // The standard deviation of ln ratio(), to first order in the per-value terms.
  double log_ratio_sigma() const {
    const double k = double(count_), ms = s_ / k, mn = n_ / k;
    const double vs = ss_ / k - ms * ms, vn = nn_ / k - mn * mn, c = sn_ / k - ms * mn;
    return std::sqrt(std::max(0.0, vs / (ms * ms) + vn / (mn * mn) - 2.0 * c / (ms * mn)) / k);
  }
  bool has_noise() const { return n_ > 0; }

 private:
  static double sq(double x) { return x * x; }
  uint64_t count_ = 0;
  double s_ = 0, n_ = 0, ss_ = 0, nn_ = 0, sn_ = 0;
};

// Number of standard errors a statistical test allows: a correct estimator fails a two-sided
// check at 4.5 sigma with probability about 7e-6 (and the seeds are fixed, so never flakily).
inline constexpr double kSigmas = 4.5;

}  // namespace prism::test
