#include "core/film.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace prism {

Film::Film(int width, int height) : width_(width), height_(height) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("film size must be positive, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  pixels_.resize(size_t(width) * size_t(height));
}

void Film::mean(int x, int y, float rgba[4]) const {
  const Pixel& px = pixel(x, y);
  const double inv = px.count ? 1.0 / double(px.count) : 0.0;
  for (int c = 0; c < 4; ++c) rgba[c] = static_cast<float>(px.sum[c] * inv);
}

Rgb Film::variance_of_mean(int x, int y) const {
  const Pixel& px = pixel(x, y);
  if (px.count < 2) return Rgb(0.0f);
  const double n = double(px.count);
  float v[3];
  for (int c = 0; c < 3; ++c) {
    // Sum-of-squares form in double: relative cancellation error ~1e-16 * n, far below the noise.
    const double sample_variance = std::max(0.0, (px.sum_sq[c] - px.sum[c] * px.sum[c] / n) / (n - 1));
    v[c] = static_cast<float>(sample_variance / n);
  }
  return {v[0], v[1], v[2]};
}

std::vector<float> Film::resolve_rgba() const {
  std::vector<float> out(size_t(width_) * height_ * 4);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) mean(x, y, &out[(size_t(y) * width_ + x) * 4]);
  return out;
}

std::vector<float> Film::resolve_counts() const {
  std::vector<float> out(pixels_.size());
  for (size_t i = 0; i < pixels_.size(); ++i) out[i] = static_cast<float>(pixels_[i].count);
  return out;
}

}  // namespace prism
