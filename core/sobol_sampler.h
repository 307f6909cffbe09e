// SobolSampler: Owen-scrambled Sobol samples, padded in 2D; every pixel and dimension pair is
// shuffled and scrambled independently (Burley 2020, section 4; pbrt-v4's PaddedSobolSampler).
#pragma once

#include <cstdint>

#include "core/hash.h"
#include "core/owen_sobol.h"
#include "core/sampler.h"

namespace prism {

// Each next_1d / next_2d call is its own dimension: it draws point `index` of a sequence whose
// order is shuffled by Owen-scrambling the index, and whose values are Owen-scrambled, both seeded
// by a hash of (pixel, dimension, seed). The first 2^m samples of a pixel thus form a (0,m,2)-net
// in every 2D draw (jittered in every stratum shape) and are stratified in every 1D draw, while
// different dimensions and pixels stay uncorrelated. Sample indices are taken modulo 2^32.
class SobolSampler final : public Sampler {
 public:
  explicit SobolSampler(uint64_t seed) : seed_(seed) {}

  void start_pixel_sample(int x, int y, uint64_t index) override {
    if (x != x_ || y != y_) {
      x_ = x;
      y_ = y;
      pixel_hash_ = hash_values(static_cast<uint64_t>(x), static_cast<uint64_t>(y), seed_, 0x50b01ull);
      cached_ = 0;
    }
    reversed_index_ = reverse_bits(static_cast<uint32_t>(index));
    dimension_ = 0;
  }

  // The Owen scramble of a fraction v is reverse(LK(reverse(v))). With r = reverse(i) for the
  // shuffled index i, dimension 0 (the radical inverse, r itself) scrambles to reverse(LK(i)) and
  // dimension 1 to reverse(LK(reverse(sobol_dim1(i)))), which the tables give straight from r.
  float next_1d() override {
    const Seeds s = next_seeds();
    const uint32_t r = laine_karras_permutation(reversed_index_, s.index);
    return fraction_to_float(owen_scramble(r, s.value0));
  }

  Vec2 next_2d() override {
    const Seeds s = next_seeds();
    const uint32_t r = laine_karras_permutation(reversed_index_, s.index);
    const uint32_t x = laine_karras_permutation(reverse_bits(r), s.value0);
    const uint32_t y = laine_karras_permutation(sobol_dim1_reversed(r), s.value1);
    const uint64_t xy = reverse_bits64((uint64_t(y) << 32) | x);  // both reversed at once
    return {fraction_to_float(uint32_t(xy >> 32)), fraction_to_float(uint32_t(xy))};
  }

 private:
  struct Seeds {
    uint32_t index, value0, value1;
  };

  // The seeds of a dimension depend on the pixel, not the sample index: consecutive samples of a
  // pixel reuse them from a small cache.
  Seeds next_seeds() {
    const uint32_t d = dimension_++;
    if (d < cached_) return cache_[d];
    const uint64_t h = hash_combine(pixel_hash_, d);
    const Seeds s{uint32_t(h), uint32_t(h >> 32), uint32_t(mix64(h))};
    if (d == cached_ && d < kCachedDimensions) cache_[cached_++] = s;
    return s;
  }

  static constexpr uint32_t kCachedDimensions = 64;
  uint64_t seed_;
  int x_ = -1, y_ = -1;
  uint64_t pixel_hash_ = 0;
  uint32_t reversed_index_ = 0;
  uint32_t dimension_ = 0;
  uint32_t cached_ = 0;
  Seeds cache_[kCachedDimensions] = {};
};

}  // namespace prism
