// Sampler: the source of sample values for one pixel sample, a pure function of
// (pixel, sample index, dimension, seed) so images never depend on thread scheduling.
#pragma once

#include <cstdint>

#include "core/hash.h"
#include "core/pcg32.h"
#include "core/vec3.h"

namespace prism {

// Where a sampler stands in its pixel's samples: the sample index, and how many draws it made of
// that sample (its dimension, as the sampler counts them).
struct SamplerPosition {
  uint64_t index = 0;
  uint32_t dimension = 0;
};

// The draws a path tracer makes at each vertex of a path, in the order a sampler hands them out.
struct VertexSamples {
  float light_spare = 0;  // places the light point where light_point.x runs short (1D): Emitters::sample
  Vec2 light_point;       // which light, and where on it (2D)
  float lobe = 0;         // which BSDF lobe (1D)
  Vec2 direction;         // the scattered direction (2D)
  float roulette = 0;     // Russian roulette (1D)
};

class Sampler {
 public:
  virtual ~Sampler() = default;
  // Positions the sampler at sample `index` of pixel (x, y), dimension 0.
  virtual void start_pixel_sample(int x, int y, uint64_t index) = 0;
  virtual float next_1d() = 0;
  virtual SamplerPosition position() const = 0;
  // Moves to another position of the same pixel: the values then drawn are those
  // start_pixel_sample(x, y, to.index) and to.dimension draws after it would give. Path splitting
  // (PathIntegrator) draws each continuation of a camera sample from a sample index of its own.
  virtual void move_to(const SamplerPosition& to) = 0;
  virtual Vec2 next_2d() {
    const float a = next_1d();
    return {a, next_1d()};
  }
  // Five draws at once, the values next_1d, next_2d, next_1d, next_2d, next_1d would give (Sobol
  // draws the light point jointly with the bounce before it instead: SobolSampler), written
  // into `v` where the caller keeps them: returned through a temporary, the copy's wide loads of
  // the callee's narrow stores stalled on store forwarding (docs/PERFORMANCE.md, session 44).
  virtual void draw_vertex(VertexSamples& v) {
    v.light_spare = next_1d();
    v.light_point = next_2d();
    v.lobe = next_1d();
    v.direction = next_2d();
    v.roulette = next_1d();
  }
  VertexSamples next_vertex() {
    VertexSamples v;
    draw_vertex(v);
    return v;
  }
};

// Independent uniform samples: pixel and seed choose a PCG32 stream; each sample index starts at
// a hashed position in it and consumes one value per dimension. Windows of different samples
// could overlap only if two hashed starts fell within a path's length of each other in a 2^64
// period: negligible, and far cheaper than jumping ahead by index x 2^16 (O(log n) steps).
class IndependentSampler final : public Sampler {
 public:
  explicit IndependentSampler(uint64_t seed) : seed_(seed) {}

  void start_pixel_sample(int x, int y, uint64_t index) override {
    x_ = x;
    y_ = y;
    at_ = {index, 0};
    rng_.seed(hash_values(static_cast<uint64_t>(x), static_cast<uint64_t>(y), seed_), hash_values(index, seed_));
  }
  float next_1d() override {
    ++at_.dimension;
    return rng_.next_float();
  }
  SamplerPosition position() const override { return at_; }
  void move_to(const SamplerPosition& to) override {
    start_pixel_sample(x_, y_, to.index);
    at_.dimension = to.dimension;
    rng_.advance(to.dimension);  // one value per draw
  }

 private:
  uint64_t seed_;
  Pcg32 rng_;
  int x_ = 0, y_ = 0;
  SamplerPosition at_;
};

}  // namespace prism
