// SobolSampler: Owen-scrambled Sobol samples, padded in 2D (Burley 2020, section 4; pbrt-v4's
// PaddedSobolSampler), but for a vertex's light point, drawn as one 4D net with the bounce before it.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>

#include "core/hash.h"
#include "core/owen_sobol.h"
#include "core/owen_sobol_vertex.h"
#include "core/sampler.h"
#include "core/sobol_seed_cache.h"

namespace prism {

// Each next_1d / next_2d call is its own dimension: it draws point `index` of a sequence whose
// order is shuffled by Owen-scrambling the index, and whose values are Owen-scrambled, both seeded
// by a hash of (pixel, dimension, seed). The first 2^m samples of a pixel thus form a (0,m,2)-net
// in every 2D draw (jittered in every stratum shape) and are stratified in every 1D draw, while
// different dimensions and pixels stay uncorrelated. Sample indices are taken modulo 2^32.
class SobolSampler final : public Sampler {
 public:
  // A sampler with seed caches of its own.
  explicit SobolSampler(uint64_t seed) : SobolSampler(std::make_shared<SobolSeedCache>(seed, 1)) {}
  // A sampler drawing seeds from `cache` (and with its seed), shared with the other lanes of a packet.
  explicit SobolSampler(std::shared_ptr<SobolSeedCache> cache)
      : cache_(std::move(cache)), entry_(cache_->take(-1, -1, -1)) {}
  // A copy draws the same values from caches of its own.
  SobolSampler(const SobolSampler& other)
      : cache_(std::make_shared<SobolSeedCache>(other.cache_->seed(), 1)),
        entry_(cache_->take(-1, other.cache_->entry(other.entry_).x, other.cache_->entry(other.entry_).y)),
        reversed_index_(other.reversed_index_), dimension_(other.dimension_) {}
  SobolSampler& operator=(const SobolSampler&) = delete;
  ~SobolSampler() override { cache_->release(entry_); }

  void start_pixel_sample(int x, int y, uint64_t index) override {
    entry_ = cache_->take(entry_, x, y);
    reversed_index_ = reverse_bits(static_cast<uint32_t>(index));
    dimension_ = 0;
  }

  SamplerPosition position() const override { return {reverse_bits(reversed_index_), dimension_}; }
  void move_to(const SamplerPosition& to) override {
    reversed_index_ = reverse_bits(static_cast<uint32_t>(to.index));
    dimension_ = to.dimension;
  }

  float next_1d() override { return owen_sobol_1d(reversed_index_, next_seeds()); }
  Vec2 next_2d() override { return owen_sobol_2d(reversed_index_, next_seeds()); }
  // A vertex's five draws, as next_1d, next_2d, next_1d, next_2d, next_1d would make them but for
  // the light point: drawn at dimension L, it shares the index shuffle of dimension max(L - 3, 0)
  // (owen_sobol_2d_joint), which is the bounce direction that reached the vertex when vertices are
  // drawn one after another, and the camera's jitter (dimension 0) for the first. The two are then
  // one 4D net rather than independently padded pairs: the light a bounce finds is integrated over
  // the bounce and the light point together (relMSE at 64 spp 0-4% lower on the canonical scenes,
  // docs/PERFORMANCE.md, session 49).
  void draw_vertex(VertexSamples& v) override {
    if (!owen_sobol_vertex_available()) return draw_vertex_one_at_a_time(v);
    const uint32_t d = dimension_;
    SobolSeedCache::Entry& e = cache_->entry(entry_);
    if (d + 5 <= e.cached) {  // the usual case: every seed from the cache, as it lies
      dimension_ += 5;
      owen_sobol_vertex(reversed_index_, {e.index + d, e.value0 + d, e.value1 + d}, e.index[partner_of(d)], v);
    } else {
      const uint32_t partner = cache_->seeds(e, partner_of(d)).index;
      SeedRun run;
      for (int k = 0; k < 5; ++k) run.set(k, next_seeds());  // in order, filling the cache
      owen_sobol_vertex(reversed_index_, {run.index, run.value0, run.value1}, partner, v);
    }
  }
  // The same values without AVX2, one draw at a time.
  void draw_vertex_one_at_a_time(VertexSamples& v) {
    const uint32_t partner = cache_->seeds(cache_->entry(entry_), partner_of(dimension_)).index;
    v.light_spare = next_1d();
    v.light_point = owen_sobol_2d_joint(reversed_index_, partner, next_seeds());
    v.lobe = next_1d();
    v.direction = next_2d();
    v.roulette = next_1d();
  }

 private:
  SobolSeeds next_seeds() { return cache_->seeds(cache_->entry(entry_), dimension_++); }
  // The dimension whose index shuffle the light point of a vertex starting at dimension d shares:
  // the light point is d + 1, the previous vertex's direction d - 2.
  static uint32_t partner_of(uint32_t d) { return d >= 2 ? d - 2 : 0; }

  // Five dimensions' seeds outside the cache, padded for owen_sobol_vertex's eight-wide loads.
  struct SeedRun {
    uint32_t index[8] = {}, value0[8] = {}, value1[8] = {};
    void set(int k, const SobolSeeds& s) {
      index[k] = s.index;
      value0[k] = s.value0;
      value1[k] = s.value1;
    }
  };

  std::shared_ptr<SobolSeedCache> cache_;
  int entry_;  // this sampler's pixel in cache_ (pixel (-1, -1) until started)
  uint32_t reversed_index_ = 0;
  uint32_t dimension_ = 0;
};

}  // namespace prism
