#include "core/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/vec3.h"

namespace prism {
namespace {

void check_sizes(const ImageDesc& t, const ImageDesc& r) {
  if (t.width != r.width || t.height != r.height)
    throw std::invalid_argument("image sizes differ: " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                                " vs " + std::to_string(r.width) + "x" + std::to_string(r.height));
  if (t.channels < 1 || r.channels < 1) throw std::invalid_argument("an image has no channels");
}

// Colour channel c of pixel i (grey images repeat their one channel).
float colour(const ImageDesc& img, size_t i, int c) {
  return img.texels[i * size_t(img.channels) + size_t(img.channels >= 3 ? c : 0)];
}

bool finite_colour(const ImageDesc& img, size_t i) {
  for (int c = 0; c < 3; ++c)
    if (!std::isfinite(colour(img, i, c))) return false;
  return true;
}

}  // namespace

ImageComparison compare_images(const ImageDesc& test, const ImageDesc& reference) {
  check_sizes(test, reference);
  ImageComparison out;
  const size_t n = size_t(test.width) * size_t(test.height);
  std::array<double, 3> sum_t{}, sum_r{}, sum_sq{}, sum_rel{};
  for (size_t i = 0; i < n; ++i) {
    const bool ft = finite_colour(test, i), fr = finite_colour(reference, i);
    out.nonfinite_test += !ft;
    out.nonfinite_reference += !fr;
    if (!ft || !fr) continue;
    ++out.pixels;
    for (int c = 0; c < 3; ++c) {
      const double t = colour(test, i, c), r = colour(reference, i, c), d = t - r;
      sum_t[c] += t;
      sum_r[c] += r;
      sum_sq[c] += d * d;
      sum_rel[c] += d * d / (r * r + kRelMseEpsilon);
      out.channel[c].max_abs = std::max(out.channel[c].max_abs, std::abs(d));
    }
  }
  const double count = double(std::max<uint64_t>(out.pixels, 1));
  for (int c = 0; c < 3; ++c) {
    ChannelError& e = out.channel[c];
    e.mean_test = sum_t[c] / count;
    e.mean_reference = sum_r[c] / count;
    e.mse = sum_sq[c] / count;
    e.rel_mse = sum_rel[c] / count;
    out.all.mean_test += e.mean_test / 3;
    out.all.mean_reference += e.mean_reference / 3;
    out.all.mse += e.mse / 3;
    out.all.rel_mse += e.rel_mse / 3;
    out.all.max_abs = std::max(out.all.max_abs, e.max_abs);
  }
  out.rmse = std::sqrt(out.all.mse);
  // The luminance's relative error, against a floor of the reference's mean luminance (luminance
  // is linear: that of the channels' means).
  auto luminance_of = [](const ImageDesc& img, size_t i) {
    return luminance(Rgb(colour(img, i, 0), colour(img, i, 1), colour(img, i, 2)));
  };
  const Rgb reference_mean(float(out.channel[0].mean_reference), float(out.channel[1].mean_reference),
                           float(out.channel[2].mean_reference));
  const double floor = std::max(kRelativeErrorFloor * luminance(reference_mean), 1e-30);
  std::vector<double> errors;
  errors.reserve(out.pixels);
  double sum_sq_error = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!finite_colour(test, i) || !finite_colour(reference, i)) continue;
    const double r = luminance_of(reference, i);
    errors.push_back(std::abs(luminance_of(test, i) - r) / std::max(r, floor));
    sum_sq_error += errors.back() * errors.back();
  }
  if (!errors.empty()) {
    out.relative_error_rms = std::sqrt(sum_sq_error / double(errors.size()));
    std::nth_element(errors.begin(), errors.begin() + ptrdiff_t(errors.size() / 2), errors.end());
    out.relative_error_median = errors[errors.size() / 2];
  }
  out.psnr = out.all.mse > 0 ? -10.0 * std::log10(out.all.mse) : std::numeric_limits<double>::infinity();
  return out;
}

std::vector<float> relative_error_map(const ImageDesc& test, const ImageDesc& reference) {
  check_sizes(test, reference);
  const size_t n = size_t(test.width) * size_t(test.height);
  std::vector<float> out(n, 0.0f);
  for (size_t i = 0; i < n; ++i) {
    if (!finite_colour(test, i) || !finite_colour(reference, i)) continue;
    double sum = 0;
    for (int c = 0; c < 3; ++c) {
      const double r = colour(reference, i, c), d = colour(test, i, c) - r;
      sum += d * d / (r * r + kRelMseEpsilon);
    }
    out[i] = float(std::sqrt(sum / 3));
  }
  return out;
}

}  // namespace prism
