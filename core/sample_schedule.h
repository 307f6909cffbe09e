// SampleSchedule: how many samples each pixel gets in each progressive pass, from the budgets
// (fixed spp, wall-clock time, noise target), the allocation and the film's own noise estimates.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/film.h"
#include "core/render_settings.h"

namespace prism {

// The names RenderSettings::allocation takes, the default first.
std::vector<std::string> allocation_names();

class SampleSchedule {
 public:
  SampleSchedule(const RenderSettings& settings, int width, int height);

  // Fills `target` with each pixel's sample count at the end of the next pass (a pixel's samples
  // run from its current count up to its target). Returns false when the render is complete.
  // `seconds` and `samples` are the rendering time and samples taken so far. A film that holds
  // samples already (a resumed render) continues from each pixel's count.
  bool next_pass(const Film& film, double seconds, uint64_t samples, std::vector<uint32_t>& target);

  bool adaptive() const { return noise_target_ > 0; }
  bool progressive() const { return time_budget_ > 0 || noise_target_ > 0 || by_error_; }
  int passes() const { return passes_; }
  // Samples a whole render is expected to take, for progress reports (an estimate under budgets).
  uint64_t expected_samples() const { return expected_samples_; }

  // Whether the noise target measures the sampler's own error from the film's half sums: a noise
  // target with a stratified sampler whose sample indices start at 0 (so that power-of-two blocks
  // of a pixel's samples are nets). The film must then track_halves(), as render() has it do.
  bool uses_halves() const { return uses_halves_; }

  // Estimated relative standard error of a pixel's luminance as if its samples were independent:
  // the standard error (the channels' errors added, a bound reached when they are fully
  // correlated, as they nearly are) over the larger of the pixel's luminance and a floor of 1% of
  // the image's mean luminance.
  double relative_error(const Film& film, int x, int y) const;
  // Every pixel's estimated relative error, top row first: relative_error, scaled down by the
  // sampler's stratification (core/stratified_error.h) when the film tracks halves.
  std::vector<double> estimated_errors(const Film& film) const;
  // The image's estimated error (the EXR header's prism/relativeError, and what a noise target
  // shared by error bounds): the RMS over pixels of `estimated` (estimated_errors(film), which the
  // caller may need too), each over its 3x3 block's mean luminance rather than its own (see
  // sample_schedule.cpp). Needs update_floor first.
  double image_error(const Film& film, const std::vector<double>& estimated) const;
  // Each pixel's error as the noise target judges it: the larger of its own estimated error and
  // the mean of its neighbours' that are not 0, each taken at this pixel's sample count (see
  // sample_schedule.cpp).
  std::vector<double> judged_errors(const Film& film) const;
  // Measures that floor from the film (done before each adaptive pass).
  void update_floor(const Film& film);

 private:
  // Shared by error under a fixed spp, no pixel takes more than this many times the mean spp.
  static constexpr uint32_t kErrorAllocationCeiling = 16;

  uint32_t max_spp_;
  uint32_t min_spp_;
  uint32_t mean_spp_ = 0;  // fixed spp shared by error: the mean each pass's total is capped by
  uint64_t cap_increments(const std::vector<uint32_t>& counts, std::vector<uint32_t>& target, double affordable) const;

  double time_budget_, pass_seconds_, noise_target_;
  bool by_error_;
  bool uses_halves_;
  size_t pixels_;
  int passes_ = 0;
  double floor_ = 1e-30;
  uint64_t expected_samples_;
};

}  // namespace prism
