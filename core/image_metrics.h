// Image error metrics between a test image and a reference: RMSE, relative MSE, PSNR, maximum difference,
// and the luminance's relative error per pixel that the noise target aims at.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/scene_desc.h"

namespace prism {

struct ChannelError {
  double mean_test = 0, mean_reference = 0;
  double mse = 0;      // mean of (t - r)^2
  double rel_mse = 0;  // mean of (t - r)^2 / (r^2 + epsilon)
  double max_abs = 0;  // largest |t - r|
};

struct ImageComparison {
  std::array<ChannelError, 3> channel;  // R, G, B (a single-channel image fills all three)
  ChannelError all;                     // over the three colour channels together
  double rmse = 0;
  double psnr = 0;                      // dB against a peak of 1 (display white); infinite when equal
  uint64_t nonfinite_test = 0, nonfinite_reference = 0;  // pixels left out of every figure
  uint64_t pixels = 0;                  // pixels compared
  // The luminance's relative error per pixel, |t - r| / max(r, kRelativeErrorFloor x the reference's
  // mean luminance): the measure `--noise` bounds (SampleSchedule::relative_error estimates it).
  // Root mean square and median over the pixels compared.
  double relative_error_rms = 0, relative_error_median = 0;
};

// relMSE's epsilon keeps near-black reference pixels from dominating (Rousselle, Knaus and
// Zwicker, "Adaptive sampling and reconstruction using greedy error minimization", 2011).
inline constexpr double kRelMseEpsilon = 1e-2;

// A pixel's relative error is taken against at least this fraction of the image's mean luminance,
// so that black pixels have a finite one.
inline constexpr double kRelativeErrorFloor = 1e-2;

// Compares the colour channels of `test` with `reference`, which must be the same size.
// Throws std::invalid_argument when the sizes differ.
ImageComparison compare_images(const ImageDesc& test, const ImageDesc& reference);

// Per-pixel relative error sqrt(mean over R,G,B of (t - r)^2 / (r^2 + epsilon)), 0 for pixels with a
// non-finite value; for difference images.
std::vector<float> relative_error_map(const ImageDesc& test, const ImageDesc& reference);

}  // namespace prism
