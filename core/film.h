// Film: per-pixel sums of radiance and alpha in double, with sample counts.
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
    Pixel& px = pixels_[size_t(y) * width_ + x];
    px.r += radiance.x;
    px.g += radiance.y;
    px.b += radiance.z;
    px.a += alpha;
    px.count += 1;
  }

  // Mean of the samples of pixel (x, y) as RGBA; zero for a pixel with no samples.
  void mean(int x, int y, float rgba[4]) const;
  uint64_t sample_count(int x, int y) const { return pixels_[size_t(y) * width_ + x].count; }

  // All pixels as interleaved RGBA float, top row first.
  std::vector<float> resolve_rgba() const;

 private:
  struct Pixel {
    double r = 0, g = 0, b = 0, a = 0;
    uint64_t count = 0;
  };
  int width_, height_;
  std::vector<Pixel> pixels_;
};

}  // namespace prism
