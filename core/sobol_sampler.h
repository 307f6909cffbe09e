// SobolSampler: Owen-scrambled Sobol samples, padded in 2D; every pixel and dimension pair is
// shuffled and scrambled independently (Burley 2020, section 4; pbrt-v4's PaddedSobolSampler).
#pragma once

#include <cstdint>

#include "core/hash.h"
#include "core/owen_sobol.h"
#include "core/owen_sobol_vertex.h"
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

  float next_1d() override { return owen_sobol_1d(reversed_index_, next_seeds()); }
  Vec2 next_2d() override { return owen_sobol_2d(reversed_index_, next_seeds()); }
  VertexSamples next_vertex() override {
    if (!owen_sobol_vertex_available()) return Sampler::next_vertex();  // one draw at a time
    float u[7];
    const uint32_t d = dimension_;
    if (d + 5 <= cached_) {  // the usual case: every seed from the cache, as it lies
      dimension_ += 5;
      owen_sobol_vertex(reversed_index_, {index_seed_ + d, value0_seed_ + d, value1_seed_ + d}, u);
    } else {
      SeedRun run;
      for (int k = 0; k < 5; ++k) run.set(k, next_seeds());  // in order, filling the cache
      owen_sobol_vertex(reversed_index_, {run.index, run.value0, run.value1}, u);
    }
    return {u[0], {u[1], u[2]}, u[3], {u[4], u[5]}, u[6]};
  }

 private:
  // The seeds of a dimension depend on the pixel, not the sample index: consecutive samples of a
  // pixel reuse them from a small cache, kept as arrays that owen_sobol_vertex loads directly.
  SobolSeeds next_seeds() {
    const uint32_t d = dimension_++;
    if (d < cached_) return {index_seed_[d], value0_seed_[d], value1_seed_[d]};
    const uint64_t h = hash_combine(pixel_hash_, d);
    const SobolSeeds s{uint32_t(h), uint32_t(h >> 32), uint32_t(mix64(h))};
    if (d == cached_ && d < kCachedDimensions) {
      index_seed_[d] = s.index;
      value0_seed_[d] = s.value0;
      value1_seed_[d] = s.value1;
      ++cached_;
    }
    return s;
  }

  // Five dimensions' seeds outside the cache, padded for owen_sobol_vertex's eight-wide loads.
  struct SeedRun {
    uint32_t index[8] = {}, value0[8] = {}, value1[8] = {};
    void set(int k, const SobolSeeds& s) {
      index[k] = s.index;
      value0[k] = s.value0;
      value1[k] = s.value1;
    }
  };

  static constexpr uint32_t kCachedDimensions = 64;
  static constexpr uint32_t kPadding = 8;  // owen_sobol_vertex reads eight seeds from the run's start
  uint64_t seed_;
  int x_ = -1, y_ = -1;
  uint64_t pixel_hash_ = 0;
  uint32_t reversed_index_ = 0;
  uint32_t dimension_ = 0;
  uint32_t cached_ = 0;
  uint32_t index_seed_[kCachedDimensions + kPadding] = {};
  uint32_t value0_seed_[kCachedDimensions + kPadding] = {};
  uint32_t value1_seed_[kCachedDimensions + kPadding] = {};
};

}  // namespace prism
