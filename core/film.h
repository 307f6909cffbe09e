// Film: per-pixel sums of radiance, squared radiance and alpha in double, with sample counts.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace prism {

class Film {
 public:
  Film(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }

  // Adds one sample; only the thread rendering the pixel's tile may call it for that pixel.
  void add_sample(int x, int y, const Rgb& radiance, float alpha) {
    Pixel& px = pixel(x, y);
    px.sum[0] += radiance.x;
    px.sum[1] += radiance.y;
    px.sum[2] += radiance.z;
    px.sum[3] += alpha;
    px.sum_sq[0] += double(radiance.x) * radiance.x;
    px.sum_sq[1] += double(radiance.y) * radiance.y;
    px.sum_sq[2] += double(radiance.z) * radiance.z;
    px.count += 1;
  }

  // Mean of the samples of pixel (x, y) as RGBA; zero for a pixel with no samples.
  void mean(int x, int y, float rgba[4]) const;
  uint64_t sample_count(int x, int y) const { return pixel(x, y).count; }
  // Unbiased estimate of the variance of the pixel's mean (sample variance / n) per colour
  // channel; zero with fewer than two samples.
  Rgb variance_of_mean(int x, int y) const;

  // All pixels as interleaved RGBA float, top row first.
  std::vector<float> resolve_rgba() const;
  // Samples per pixel, top row first.
  std::vector<float> resolve_counts() const;

 private:
  struct Pixel {
    double sum[4] = {0, 0, 0, 0};
    double sum_sq[3] = {0, 0, 0};
    uint64_t count = 0;
  };
  Pixel& pixel(int x, int y) { return pixels_[size_t(y) * width_ + x]; }
  const Pixel& pixel(int x, int y) const { return pixels_[size_t(y) * width_ + x]; }

  int width_, height_;
  std::vector<Pixel> pixels_;
};

}  // namespace prism
