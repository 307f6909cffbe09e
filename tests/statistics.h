// Running mean and variance (Welford) for statistical tests, with the standard error of the mean.
#pragma once

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

// Number of standard errors a statistical test allows: a correct estimator fails a two-sided
// check at 4.5 sigma with probability about 7e-6 (and the seeds are fixed, so never flakily).
inline constexpr double kSigmas = 4.5;

}  // namespace prism::test
