#include "core/film.h"

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
  const Pixel& px = pixels_[size_t(y) * width_ + x];
  const double inv = px.count ? 1.0 / double(px.count) : 0.0;
  rgba[0] = static_cast<float>(px.r * inv);
  rgba[1] = static_cast<float>(px.g * inv);
  rgba[2] = static_cast<float>(px.b * inv);
  rgba[3] = static_cast<float>(px.a * inv);
}

std::vector<float> Film::resolve_rgba() const {
  std::vector<float> out(size_t(width_) * height_ * 4);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) mean(x, y, &out[(size_t(y) * width_ + x) * 4]);
  return out;
}

}  // namespace prism
