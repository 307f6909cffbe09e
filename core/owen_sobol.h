// Owen-scrambled Sobol points by hashing (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4)).
#pragma once

#include <array>
#include <cstdint>

#include "core/vec3.h"

namespace prism {

// The bit operations below are templates so that a vector of 32-bit lanes (GCC vector extensions,
// core/owen_sobol_vertex.cpp) runs the very same code as a single uint32_t. They work in place,
// through references, and are always inlined: a 32-byte vector passed by value to a function
// built without AVX would change its ABI (an error in Clang), and inlined, the lanes compile for
// the caller's instruction set.
template <class U32>
[[gnu::always_inline]] constexpr void reverse_bits_in_place(U32& x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  x = (x >> 16) | (x << 16);
}
constexpr uint32_t reverse_bits(uint32_t x) {
  reverse_bits_in_place(x);
  return x;
}

// Two 32-bit reversals in one: reverse_bits64((hi << 32) | lo) = (reverse_bits(lo) << 32) | reverse_bits(hi).
constexpr uint64_t reverse_bits64(uint64_t x) {
  x = ((x >> 1) & 0x5555555555555555ull) | ((x & 0x5555555555555555ull) << 1);
  x = ((x >> 2) & 0x3333333333333333ull) | ((x & 0x3333333333333333ull) << 2);
  x = ((x >> 4) & 0x0f0f0f0f0f0f0f0full) | ((x & 0x0f0f0f0f0f0f0f0full) << 4);
  x = ((x >> 8) & 0x00ff00ff00ff00ffull) | ((x & 0x00ff00ff00ff00ffull) << 8);
  x = ((x >> 16) & 0x0000ffff0000ffffull) | ((x & 0x0000ffff0000ffffull) << 16);
  return (x >> 32) | (x << 32);
}

// A random bijection in which each output bit depends only on the input bits below it (Laine and
// Karras 2011), with the stronger constants of N. Vegdahl, "Building a better LK hash" (2021).
// XOR with a multiple by an even number, adding, and multiplying by an odd number each keep that
// property, so the composition is a hash-driven base-2 Owen scramble of the bit-reversed value.
template <class U32>
[[gnu::always_inline]] constexpr void laine_karras_permute_in_place(U32& x, const U32& seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
}
constexpr uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  laine_karras_permute_in_place(x, seed);
  return x;
}

// Nested uniform (Owen) scrambling of a 32-bit binary fraction: bit k of the result is flipped by
// a function of the bits above it, so every dyadic interval maps onto one of the same size.
constexpr uint32_t owen_scramble(uint32_t x, uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

// Sobol's second dimension from the primitive polynomial x + 1: direction numbers
// v_k = v_(k-1) xor v_(k-1) >> 1 from v_0 = 1/2, Pascal's triangle mod 2. With the first dimension
// (van der Corput's radical inverse, the bit-reversed index) it forms a (0,2)-sequence: any 2^m
// consecutive points aligned to a multiple of 2^m put one point in every dyadic box of area 2^-m.
//
// The tables work on the bit-reversed index r = reverse_bits(i), which is dimension 0 itself,
// and hold the result bit-reversed too, ready for the scramble: byte b of r selects the XOR of
// the columns for index bits 31-8b-7 .. 31-8b.
struct SobolDim1Tables {
  std::array<std::array<uint32_t, 256>, 4> table{};
  constexpr SobolDim1Tables() {
    std::array<uint32_t, 32> column{};  // column[k]: index bit k's contribution, bit-reversed
    uint32_t v = 0x80000000u;
    for (int k = 0; k < 32; ++k) {
      column[k] = reverse_bits(v);
      v ^= v >> 1;
    }
    for (int b = 0; b < 4; ++b)
      for (uint32_t byte = 0; byte < 256; ++byte) {
        uint32_t x = 0;
        for (int j = 0; j < 8; ++j)
          if (byte & (1u << j)) x ^= column[31 - (8 * b + j)];
        table[b][byte] = x;
      }
  }
};
inline constexpr SobolDim1Tables kSobolDim1{};

// reverse_bits(sobol_dim1(reverse_bits(r))): dimension 1 of index reverse_bits(r), bit-reversed.
constexpr uint32_t sobol_dim1_reversed(uint32_t r) {
  return kSobolDim1.table[0][r & 0xff] ^ kSobolDim1.table[1][(r >> 8) & 0xff] ^ kSobolDim1.table[2][(r >> 16) & 0xff] ^
         kSobolDim1.table[3][r >> 24];
}

// The same as sobol_dim1_reversed(reverse_bits(i)), i.e. reverse_bits(sobol_dim1(i)), without
// tables, for vector lanes. Index bit k adds row k of Pascal's triangle mod 2, and C(k, j) is odd
// exactly when the bits of j are a subset of those of k (Lucas' theorem), so bit j of the result is
// the XOR of the index bits k that are supersets of j: a superset transform over the five bits of
// a bit position, one butterfly per bit. Scalar draws keep the tables, which read r in parallel
// with its reversal: the transform's chain after it made one-at-a-time draws 5% slower
// (BM_SamplerPath<SobolSampler>/0, 214 -> 225 ns).
template <class U32>
[[gnu::always_inline]] constexpr void reversed_sobol_dim1_in_place(U32& i) {
  i ^= (i >> 1) & 0x55555555u;
  i ^= (i >> 2) & 0x33333333u;
  i ^= (i >> 4) & 0x0f0f0f0fu;
  i ^= (i >> 8) & 0x00ff00ffu;
  i ^= i >> 16;
}

// Reference forms, for tests: dimension 1 from its direction numbers, bit by bit.
constexpr uint32_t sobol_dim1(uint32_t index) {
  uint32_t x = 0, v = 0x80000000u;
  for (; index; index >>= 1, v ^= v >> 1)
    if (index & 1u) x ^= v;
  return x;
}

// A 32-bit binary fraction as a float in [0, 1): the top 24 bits, exactly representable.
constexpr float fraction_to_float(uint32_t x) { return float(x >> 8) * 0x1p-24f; }

// The seeds of one dimension of a pixel's padded sequence: its index shuffle, and the value
// scrambles of its first and (for a 2D draw) second coordinate.
struct SobolSeeds {
  uint32_t index, value0, value1;
};

// Point `reverse_bits(reversed_index)` of one dimension, shuffled and scrambled by its seeds.
// The Owen scramble of a fraction v is reverse(LK(reverse(v))). With r = reverse(i) for the
// shuffled index i, dimension 0 (the radical inverse, r itself) scrambles to reverse(LK(i)) and
// dimension 1 to reverse(LK(reverse(sobol_dim1(i)))), which the tables give straight from r.
inline float owen_sobol_1d(uint32_t reversed_index, const SobolSeeds& s) {
  const uint32_t r = laine_karras_permutation(reversed_index, s.index);
  return fraction_to_float(owen_scramble(r, s.value0));
}

// The 2D point of the shuffled index whose reversal is r, its values scrambled by s.
inline Vec2 owen_sobol_2d_shuffled(uint32_t r, const SobolSeeds& s) {
  const uint32_t x = laine_karras_permutation(reverse_bits(r), s.value0);
  const uint32_t y = laine_karras_permutation(sobol_dim1_reversed(r), s.value1);
  const uint64_t xy = reverse_bits64((uint64_t(y) << 32) | x);  // both reversed at once
  return {fraction_to_float(uint32_t(xy >> 32)), fraction_to_float(uint32_t(xy))};
}

inline Vec2 owen_sobol_2d(uint32_t reversed_index, const SobolSeeds& s) {
  return owen_sobol_2d_shuffled(laine_karras_permutation(reversed_index, s.index), s);
}

// Two 2D draws made from one shuffled index i, the first from i and the second from
// j = i ^ (i >> 4) ^ (i >> 6) ^ (i >> 7), are one 4D point set rather than two independent ones:
// j is a linear map of i by an upper unitriangular matrix, so the first 2^m indices (an aligned
// block of i) map onto an aligned block of j, and each draw alone stays a (0,m,2)-net, while the
// four coordinates together form a (3,m,4)-net for every m <= 10 (every dyadic box of volume
// 2^(3-m) holds 8 of the 2^m points; of the sums of two or three shifts by 1 to 8, this one has
// the smallest t over m = 3..10. Sobol's dimensions 2 and 3 as the second pair give t = 2 at
// m = 4 and 6, but only t = 1 in their own 2D projection).
// A path's bounce and the light sample at the vertex it reaches are drawn so (SobolSampler).
// On the reversed index r = reverse(i), a right shift of i is a left shift of r.
template <class U32>
[[gnu::always_inline]] constexpr void joint_second_index_in_place(U32& r) {
  r ^= (r << 4) ^ (r << 6) ^ (r << 7);
}

// The second draw of such a pair: the index shuffled by the first draw's seed (partner_index),
// mapped as above, its values scrambled by its own seeds s (s.index is not used).
inline Vec2 owen_sobol_2d_joint(uint32_t reversed_index, uint32_t partner_index, const SobolSeeds& s) {
  uint32_t r = laine_karras_permutation(reversed_index, partner_index);
  joint_second_index_in_place(r);
  return owen_sobol_2d_shuffled(r, s);
}

}  // namespace prism
