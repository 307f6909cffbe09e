// Film: per-pixel sums of radiance, squared radiance and alpha in double, with sample counts, and
// the AOVs asked for (averaged sums, the nearest hit's depth and ids, Cryptomatte id counts).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/aov.h"
#include "core/id_counts.h"
#include "core/vec3.h"

namespace prism {

class Film {
 public:
  // The AOVs averaged over a pixel's samples, three components each, in this order.
  static constexpr Aov kAveraged[] = {Aov::Albedo, Aov::Normal, Aov::Position, Aov::Emission, Aov::Direct, Aov::Indirect};

  struct Pixel {
    double sum[4] = {0, 0, 0, 0};
    double sum_sq[3] = {0, 0, 0};
    uint64_t count = 0;
  };
  // A pixel's luminance sums at the two latest power-of-two counts reached since track_halves():
  // with a stratified sampler, samples [0, m) and [m, 2m) are two stratified sets of their own, and
  // the difference of their means shows the sampler's own error (core/stratified_error.h).
  struct Halves {
    double lower = 0, upper = 0;  // luminance sums at lower_count and upper_count samples
    uint64_t lower_count = 0, upper_count = 0;
    // Both sums recorded, at m and 2m samples: m = lower_count.
    bool valid() const { return lower_count > 0 && upper_count == 2 * lower_count; }
  };

  Film(int width, int height, AovSet aovs = {});

  int width() const { return width_; }
  int height() const { return height_; }
  const AovSet& aovs() const { return aovs_; }

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
    if (!halves_.empty() && (px.count & (px.count - 1)) == 0) record_halves(x, y);
  }
  // Adds the AOVs of the sample just added with add_sample: `depth` is its planar camera depth
  // (kBackgroundDepth on a miss).
  void add_aov_sample(int x, int y, const AovSample& s, float depth);
  // The Cryptomatte id (float bits) of each object and material index, for the Cryptomatte AOVs.
  void set_cryptomatte_ids(std::vector<uint32_t> objects, std::vector<uint32_t> materials) {
    object_ids_ = std::move(objects);
    material_ids_ = std::move(materials);
  }

  // Starts recording every pixel's Halves (a merge clears those of the pixels it adds samples to).
  void track_halves();
  bool tracks_halves() const { return !halves_.empty(); }
  const Halves& halves(int x, int y) const { return halves_[size_t(y) * width_ + x]; }
  Halves& halves(int x, int y) { return halves_[size_t(y) * width_ + x]; }

  // Mean of the samples of pixel (x, y) as RGBA; zero for a pixel with no samples.
  void mean(int x, int y, float rgba[4]) const;
  uint64_t sample_count(int x, int y) const { return pixel(x, y).count; }
  // The fewest and most samples any pixel has, and their total.
  struct SampleCounts {
    uint64_t min = 0, max = 0, total = 0;
  };
  SampleCounts sample_counts() const;
  // Unbiased estimate of the variance of the pixel's mean (sample variance / n) per colour
  // channel; zero with fewer than two samples.
  Rgb variance_of_mean(int x, int y) const;

  // All pixels as interleaved RGBA float, top row first.
  std::vector<float> resolve_rgba() const;
  // Samples per pixel, top row first.
  std::vector<float> resolve_counts() const;
  // Component c (0-2) of an averaged AOV's per-pixel mean, top row first.
  std::vector<float> resolve_average(Aov aov, int c) const;

  // The raw accumulators, for saving, restoring and merging partial renders.
  Pixel& pixel(int x, int y) { return pixels_[size_t(y) * width_ + x]; }
  const Pixel& pixel(int x, int y) const { return pixels_[size_t(y) * width_ + x]; }
  // Sums of the averaged AOVs: 3 per entry of kAveraged that is in aovs(), in that order.
  int average_slots() const { return average_stride_; }
  double* average_sums(int x, int y) { return &average_sums_[(size_t(y) * width_ + x) * average_stride_]; }
  const double* average_sums(int x, int y) const { return &average_sums_[(size_t(y) * width_ + x) * average_stride_]; }
  // The slot of an averaged AOV within average_sums, or -1 when it is not accumulated.
  int average_slot(Aov aov) const;
  // The nearest first hit: its depth (kBackgroundDepth when none) and object and material index.
  float& nearest_depth(int x, int y) { return nearest_depth_[size_t(y) * width_ + x]; }
  float nearest_depth(int x, int y) const { return nearest_depth_[size_t(y) * width_ + x]; }
  int32_t& nearest_object(int x, int y) { return nearest_object_[size_t(y) * width_ + x]; }
  int32_t nearest_object(int x, int y) const { return nearest_object_[size_t(y) * width_ + x]; }
  int32_t& nearest_material(int x, int y) { return nearest_material_[size_t(y) * width_ + x]; }
  int32_t nearest_material(int x, int y) const { return nearest_material_[size_t(y) * width_ + x]; }
  bool tracks_nearest() const { return !nearest_depth_.empty(); }
  std::vector<PixelIdCounts>& crypto_objects() { return crypto_objects_; }
  const std::vector<PixelIdCounts>& crypto_objects() const { return crypto_objects_; }
  std::vector<PixelIdCounts>& crypto_materials() { return crypto_materials_; }
  const std::vector<PixelIdCounts>& crypto_materials() const { return crypto_materials_; }

  // Adds another film's samples into the pixels it covers, its (0, 0) at (x0, y0) here: a
  // disjoint sample slice of the same window, or a crop placed into a larger film. Sums and counts
  // add, the nearer hit wins, Cryptomatte counts add. Throws std::invalid_argument when the AOVs
  // differ or the other film does not fit.
  void merge(const Film& other, int x0 = 0, int y0 = 0);

 private:
  void keep_nearer(size_t pixel, float depth, int32_t object, int32_t material);
  void record_halves(int x, int y);

  int width_, height_;
  AovSet aovs_;
  std::vector<Pixel> pixels_;
  std::vector<Halves> halves_;  // empty unless tracked
  int average_stride_ = 0;
  std::vector<double> average_sums_;
  std::vector<float> nearest_depth_;
  std::vector<int32_t> nearest_object_, nearest_material_;
  std::vector<PixelIdCounts> crypto_objects_, crypto_materials_;
  std::vector<uint32_t> object_ids_, material_ids_;
};

}  // namespace prism
