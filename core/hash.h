// Integer hashing used to key random streams by pixel, sample index and dimension.
#pragma once

#include <cstdint>
#include <cstring>

namespace prism {

// 64-bit finaliser of SplitMix64 (Steele et al., "Fast Splittable Pseudorandom Number
// Generators", OOPSLA 2014): a bijective mix with full avalanche.
constexpr uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

constexpr uint64_t hash_combine(uint64_t seed, uint64_t value) {
  return mix64(seed ^ (value + 0x9e3779b97f4a7c15ull + (seed << 6) + (seed >> 2)));
}

template <typename... Ts>
constexpr uint64_t hash_values(uint64_t first, Ts... rest) {
  uint64_t h = mix64(first);
  ((h = hash_combine(h, static_cast<uint64_t>(rest))), ...);
  return h;
}

// The bit pattern of a float, for hashing values that must be matched exactly.
inline uint64_t float_bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

}  // namespace prism
