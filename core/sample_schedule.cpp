#include "core/sample_schedule.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/error_allocation.h"
#include "core/image_metrics.h"
#include "core/pixel_neighbours.h"
#include "core/sampler_factory.h"
#include "core/stratified_error.h"

namespace prism {
namespace {

Rgb mean_colour(const Film& film, int x, int y) {
  float rgba[4];
  film.mean(x, y, rgba);
  return {rgba[0], rgba[1], rgba[2]};
}

}  // namespace

std::vector<std::string> allocation_names() { return {kUniformAllocation, "error"}; }

SampleSchedule::SampleSchedule(const RenderSettings& settings, int width, int height)
    : max_spp_(uint32_t(std::max(1, settings.spp))),
      min_spp_(uint32_t(std::clamp(settings.min_spp, 1, std::max(1, settings.spp)))),
      time_budget_(settings.time_budget),
      pass_seconds_(settings.pass_seconds),
      noise_target_(settings.noise_target),
      by_error_(settings.allocation == "error"),
      uses_halves_(settings.noise_target > 0 && sampler_is_stratified(settings.sampler) &&
                   settings.first_sample == 0),
      pixels_(size_t(width) * size_t(height)),
      expected_samples_(uint64_t(width) * height * max_spp_) {
  const std::vector<std::string> names = allocation_names();
  if (std::find(names.begin(), names.end(), settings.allocation) == names.end()) {
    std::string known;
    for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown allocation '" + settings.allocation + "' (known: " + known + ")");
  }
  // Under a fixed spp, spp is every pixel's count; shared by error it is the mean, and no pixel
  // takes more than kErrorAllocationCeiling times it. Under a noise target it is every pixel's
  // ceiling, shared by error or not.
  if (by_error_ && time_budget_ <= 0 && noise_target_ <= 0) {
    expected_samples_ = uint64_t(width) * height * max_spp_;
    max_spp_ = uint32_t(std::min<uint64_t>(uint64_t(max_spp_) * kErrorAllocationCeiling, 1u << 30));
    mean_spp_ = settings.spp;
  }
}

void SampleSchedule::update_floor(const Film& film) {
  double sum = 0;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) sum += luminance(mean_colour(film, x, y));
  floor_ = std::max(kRelativeErrorFloor * sum / double(pixels_), 1e-30);
}

double SampleSchedule::relative_error(const Film& film, int x, int y) const {
  const Rgb v = film.variance_of_mean(x, y);
  const double standard_error = luminance(Rgb(std::sqrt(v.x), std::sqrt(v.y), std::sqrt(v.z)));
  return standard_error / std::max(double(luminance(mean_colour(film, x, y))), floor_);
}

// With halves the estimate is Sobol's own error, not that of independent samples: on the Cornell
// box at 0.05 the real error went from 0.032 at 879 spp to 0.044 at 437, the estimate 0.042
// (docs/PERFORMANCE.md, session 52).
std::vector<double> SampleSchedule::estimated_errors(const Film& film) const {
  const int width = film.width(), height = film.height();
  std::vector<double> errors(pixels_);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) errors[size_t(y) * size_t(width) + size_t(x)] = relative_error(film, x, y);
  if (film.tracks_halves()) {
    const std::vector<double> factors = stratification_factors(film);
    for (size_t i = 0; i < pixels_; ++i) errors[i] *= std::sqrt(factors[i]);  // a factor of the variance
  }
  return errors;
}

// A pixel whose samples all missed what lights its neighbours (a run of zeros in a dim corner, say)
// has no variance of its own to show, and judged by itself would stop at min_spp with the wrong
// mean. So a pixel is judged by the larger of its own error and the mean error of its neighbours
// (the 3x3 block's others inside the image) that have any: in a noisy neighbourhood it goes on until
// the neighbourhood, too, is under the target. Neighbours with no variance either are left out of
// the mean, since theirs is the same non-evidence (with them, a pixel among other runs of misses
// stopped). Cycles' adaptive sampling guards the same way by spreading "not converged" to a
// pixel's neighbours; the mean costs fewer samples than that maximum (Cornell box at 0.05, errors
// as if independent: mean 879 spp against 1036, both under the target, where a pixel's own error
// alone took 728 and left the image at 0.064; docs/PERFORMANCE.md, session 51).
// A neighbour's error counts as it would be at this pixel's sample count (error ~ 1 / sqrt(n), the
// law of independent samples; Sobol's falls a little faster), so that a pixel is not held back by
// neighbours that merely have fewer samples than it (a rare bright light at 0.05: 1134 spp
// instead of 1209 for the same error; docs/PERFORMANCE.md, session 53).
std::vector<double> SampleSchedule::judged_errors(const Film& film) const {
  const int width = film.width(), height = film.height();
  const std::vector<double> own = estimated_errors(film);
  std::vector<double> judged(pixels_);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double count = double(std::max<uint64_t>(film.sample_count(x, y), 1));
      double sum = 0;
      int counted = 0;
      for_each_neighbour(x, y, width, height, [&](int nx, int ny) {
        const double e = own[size_t(ny) * size_t(width) + size_t(nx)];
        if (e > 0) {
          sum += e * std::sqrt(double(film.sample_count(nx, ny)) / count);
          ++counted;
        }
      });
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      judged[i] = std::max(own[i], counted > 0 ? sum / counted : 0.0);
    }
  return judged;
}

// A pixel that caught a rare bright sample (a firefly) has a large variance and a large mean at
// once, so the ratio of its own understates its error, and one that missed it shows neither:
// the RMS of the own ratios was half the real error on cornell-glass at 256 spp (0.18 against
// 0.36), and a whole-image target of 0.2 on its firefly-speckled box stopped at a real 0.33. Over
// the neighbours' mean luminance alone, which the firefly does not move, it is right there but
// twice the real error on many-lights, whose small lights are as bright and rare in their pixels
// while their neighbours are dark. So each pixel's error is taken over its 3x3 block's mean
// luminance, itself included. Estimate / real at fixed spp (own, neighbours', block): glass 0.51,
// 1.03, 0.77; many-lights 0.97, 2.24, 1.22; the Cornell box 1.01, 1.01, 0.99; the window room
// 1.12, 1.11, 1.11 (docs/PERFORMANCE.md, session 54).
double SampleSchedule::image_error(const Film& film, const std::vector<double>& estimated) const {
  const int width = film.width(), height = film.height();
  std::vector<double> luminances(pixels_);
  for (size_t i = 0; i < pixels_; ++i)
    luminances[i] = luminance(mean_colour(film, int(i % size_t(width)), int(i / size_t(width))));
  double sum = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      double block = luminances[i];
      int counted = 1;
      for_each_neighbour(x, y, width, height, [&](int nx, int ny) {
        block += luminances[size_t(ny) * size_t(width) + size_t(nx)];
        ++counted;
      });
      const double e = estimated[i] * std::max(luminances[i], floor_) / std::max(block / counted, floor_);
      sum += e * e;
    }
  return std::sqrt(sum / double(pixels_));
}

// Caps every pixel's increment (target - count) at the largest k for which the pass takes at most
// `affordable` samples, found by bisection; returns that k (0 when not even one sample each fits).
uint64_t SampleSchedule::cap_increments(const std::vector<uint32_t>& counts, std::vector<uint32_t>& target,
                                        double affordable) const {
  auto increments_capped_at = [&](uint64_t k) {
    uint64_t total = 0;
    for (size_t i = 0; i < pixels_; ++i) total += std::min<uint64_t>(target[i] - counts[i], k);
    return total;
  };
  uint64_t lo = 0, hi = max_spp_;
  while (lo < hi) {
    const uint64_t mid = (lo + hi + 1) / 2;
    if (double(increments_capped_at(mid)) <= affordable) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

bool SampleSchedule::next_pass(const Film& film, double seconds, uint64_t samples, std::vector<uint32_t>& target) {
  target.resize(pixels_);
  const int width = film.width();
  ++passes_;
  std::vector<uint32_t> counts(pixels_);  // samples each pixel has (a resumed film has some), up to the ceiling
  for (size_t i = 0; i < pixels_; ++i)
    counts[i] = uint32_t(std::min<uint64_t>(film.sample_count(int(i % size_t(width)), int(i / size_t(width))), max_spp_));
  const double per_sample = seconds / double(std::max<uint64_t>(samples, 1));  // seconds per sample so far
  auto apply_cap = [&](uint64_t k) {
    uint64_t wanted = 0;
    for (size_t i = 0; i < pixels_; ++i) {
      target[i] = counts[i] + uint32_t(std::min<uint64_t>(target[i] - counts[i], k));
      wanted += target[i] - counts[i];
    }
    return wanted;
  };

  if (!progressive()) {
    std::fill(target.begin(), target.end(), max_spp_);
    uint64_t wanted = 0;
    for (size_t i = 0; i < pixels_; ++i) wanted += max_spp_ - counts[i];
    if (passes_ == 1) expected_samples_ = wanted;
    if (pass_seconds_ > 0 && wanted > 0) {
      // Passes of about pass_seconds_ at the cost per sample measured so far, one sample per pixel
      // first. Each pixel still sums its samples in index order, so the bits are those of one pass.
      const uint64_t k = passes_ == 1 ? 1 : std::max<uint64_t>(1, cap_increments(counts, target, pass_seconds_ / per_sample));
      wanted = apply_cap(k);
    }
    return wanted > 0;
  }
  if (passes_ == 1) {
    // Every pixel first gets the minimum the noise estimate needs: min_spp for a noise target or
    // for error allocation under a fixed spp, one sample under a time budget (the image is then
    // complete as soon as possible; doubling passes bring it to min_spp before errors are judged).
    const uint32_t first = adaptive() || (by_error_ && time_budget_ <= 0) ? min_spp_ : 1u;
    uint64_t wanted = 0;
    for (size_t i = 0; i < pixels_; ++i) {
      target[i] = std::max(counts[i], first);
      wanted += target[i] - counts[i];
    }
    if (time_budget_ > 0) expected_samples_ = wanted;
    if (wanted > 0) return true;
    ++passes_;  // a resumed film has its first pass already: plan the second
  }

  if (adaptive()) update_floor(film);
  const uint64_t have = std::accumulate(counts.begin(), counts.end(), uint64_t(0));
  if (by_error_ && *std::min_element(counts.begin(), counts.end()) >= std::min(min_spp_, max_spp_)) {
    // Every pixel has its start: from here each pass doubles the film's samples at most (up to the
    // mean spp's total, what the time left affords, or what the noise target still needs) and
    // shares them by estimated error.
    uint64_t total = 2 * have;
    if (adaptive()) {
      // The whole image is judged, not each pixel: a pixel's count depends on its own samples only
      // through the image's error. A pixel stopped by its own samples is biased (darker where a rare
      // bright path was missed, as through cornell-glass's sphere: 2.5-2.7% at 0.2); here only the
      // stop of the whole render is, where rare light dominates the image's error (0.1-0.26% there,
      // against 0.01-0.05% at fixed spp; docs/PERFORMANCE.md, session 54). With the shares'
      // proportions kept, the image's mean squared error falls as 1 / total: aim 10% past the
      // estimate, since it is itself noisy.
      const double error = image_error(film, estimated_errors(film));
      if (error <= noise_target_) return false;
      const double needed = std::ceil(double(have) * (error / noise_target_) * (error / noise_target_) * 1.1);
      total = uint64_t(std::min(needed, double(total)));
      expected_samples_ = samples + (total - have);
    }
    if (time_budget_ > 0) {
      const double remaining = time_budget_ - seconds;
      const double affordable = remaining > 0 ? remaining / per_sample : 0;
      total = have + uint64_t(std::min<double>(affordable, double(total - have)));
      expected_samples_ = total;
    } else if (!adaptive()) {
      total = std::min<uint64_t>(total, uint64_t(mean_spp_) * pixels_);
    }
    if (total <= have) return false;
    // Under a noise target the shares follow the measure it bounds (a pixel's relative error e
    // after n samples, so R = e^2 n), not the relMSE, which weighs dark pixels less: the Cornell box
    // at 0.05 took 256 spp for a real 0.048 where the relMSE's shares took 512. e is taken as if
    // samples were independent: Sobol's factor pools the pixel's own halves (stratified_error.h).
    std::vector<double> weights;
    if (adaptive()) {
      std::vector<double> r(pixels_);
      for (size_t i = 0; i < pixels_; ++i) {
        const int x = int(i % size_t(width)), y = int(i / size_t(width));
        const double e = relative_error(film, x, y);
        r[i] = e * e * double(film.sample_count(x, y));
      }
      weights = neighbour_weights(r, width, film.height());
    } else {
      weights = error_weights(film);
    }
    return allocate_samples(counts, weights, total, max_spp_, target) > have;
  }
  const std::vector<double> judged = adaptive() ? judged_errors(film) : std::vector<double>{};
  uint64_t wanted = 0;
  for (size_t i = 0; i < pixels_; ++i) {
    const uint32_t count = counts[i];
    uint32_t next = count;
    // A pixel under the target is judged again each pass rather than stopped for good: with halves
    // its estimate pools its neighbours' evidence, which goes on growing after it stops (a stopped
    // pixel whose estimate rose would otherwise hold its neighbours' judged errors above the target
    // until max_spp: the window room took 44 passes instead of 9).
    if (count < max_spp_) {
      if (adaptive()) {
        const double error = judged[i];
        if (error > noise_target_) {
          // Standard error falls as 1/sqrt(n): aim 10% past the estimate, at most doubling, since
          // the estimate itself is noisy.
          const double needed = std::ceil(double(count) * (error / noise_target_) * (error / noise_target_) * 1.1);
          next = uint32_t(std::clamp<double>(needed, double(count) + 1, 2.0 * count));
        }
      } else {
        next = uint32_t(std::min<uint64_t>(2ull * count, max_spp_));
      }
      next = std::min(next, max_spp_);
    }
    target[i] = next;
    wanted += next - count;
  }

  if (time_budget_ > 0 && wanted > 0) {
    // Fit the pass into the time left at the cost per sample measured so far.
    const double remaining = time_budget_ - seconds;
    const double affordable = remaining > 0 ? remaining / per_sample : 0;
    expected_samples_ = samples + uint64_t(std::min<double>(affordable, double(wanted)));
    if (double(wanted) > affordable) {
      const uint64_t k = cap_increments(counts, target, affordable);
      if (k == 0) return false;
      wanted = apply_cap(k);
    }
  } else if (adaptive()) {
    expected_samples_ = samples + wanted;
  }
  return wanted > 0;
}

}  // namespace prism
