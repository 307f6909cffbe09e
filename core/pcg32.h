// PCG32: O'Neill's permuted congruential generator (XSH-RR output, 64-bit state), with
// stream selection and O(log n) jump-ahead (Brown, "Random Number Generation with
// Arbitrary Strides", 1994).
#pragma once

#include <cstdint>

#include "core/constants.h"

namespace prism {

class Pcg32 {
 public:
  static constexpr uint64_t kMultiplier = 0x5851f42d4c957f2dull;

  Pcg32() { seed(0x853c49e6748fea9bull, 0xda3e39cb94b95bdbull); }
  Pcg32(uint64_t sequence, uint64_t offset) { seed(sequence, offset); }

  // Selects stream `sequence` and starts it at `offset` (the pcg32_srandom_r recipe).
  void seed(uint64_t sequence, uint64_t offset) {
    state_ = 0;
    inc_ = (sequence << 1u) | 1u;
    next_u32();
    state_ += offset;
    next_u32();
  }

  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * kMultiplier + inc_;
    const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }

  // Uniform float in [0, 1): the top 24 bits, so every value is exactly representable.
  float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }

  // Moves the stream `delta` steps forward in O(log delta).
  void advance(uint64_t delta) {
    uint64_t acc_mult = 1, acc_plus = 0;
    uint64_t cur_mult = kMultiplier, cur_plus = inc_;
    while (delta > 0) {
      if (delta & 1u) {
        acc_mult *= cur_mult;
        acc_plus = acc_plus * cur_mult + cur_plus;
      }
      cur_plus = (cur_mult + 1) * cur_plus;
      cur_mult *= cur_mult;
      delta >>= 1u;
    }
    state_ = acc_mult * state_ + acc_plus;
  }

 private:
  uint64_t state_ = 0;
  uint64_t inc_ = 1;
};

}  // namespace prism
