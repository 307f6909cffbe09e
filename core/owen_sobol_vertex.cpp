#include "core/owen_sobol_vertex.h"

#include <cstring>

#include "core/cpu_features.h"

namespace prism {
namespace {

// Eight 32-bit lanes (GCC/Clang vector extensions): the bit operations of owen_sobol.h are
// templates, so the lanes run exactly the scalar code.
typedef uint32_t U32x8 __attribute__((vector_size(32)));
typedef int32_t I32x8 __attribute__((vector_size(32)));
typedef float F32x8 __attribute__((vector_size(32)));

}  // namespace

// Lanes 0-4 hold the five draws' first coordinates, lanes 5 and 6 the second coordinates of the
// two 2D draws (dimensions 1 and 3), lane 7 is idle. A 2D draw's second coordinate scrambles
// Sobol's dimension 1 of the same shuffled index, computed in the lanes from the first
// coordinate's (reversed_sobol_dim1_in_place), so no lane leaves the vector until the end. The
// light point's lanes (1 and 5) shuffle by the partner's index seed and map the index as
// owen_sobol_2d_joint does.
__attribute__((target("avx2"))) void owen_sobol_vertex(uint32_t reversed_index, const SobolSeedArrays& s,
                                                     uint32_t partner_index, VertexSamples& v) {
  U32x8 index, value0, value1;  // eight seeds from each array (unaligned loads)
  std::memcpy(&index, s.index, sizeof index);
  std::memcpy(&value0, s.value0, sizeof value0);
  std::memcpy(&value1, s.value1, sizeof value1);
  const U32x8 partner = U32x8{} + partner_index;
  const U32x8 index_seeds = __builtin_shufflevector(index, partner, 0, 8, 2, 3, 4, 8, 3, 7);
  const U32x8 value_seeds = __builtin_shufflevector(value0, value1, 0, 1, 2, 3, 4, 9, 11, 7);
  U32x8 r = U32x8{} + reversed_index;
  laine_karras_permute_in_place(r, index_seeds);
  U32x8 joint = r;
  joint_second_index_in_place(joint);
  r = __builtin_shufflevector(r, joint, 0, 9, 2, 3, 4, 13, 6, 7);
  U32x8 w = r;
  reverse_bits_in_place(w);  // the shuffled indices i
  U32x8 dim1 = w;
  reversed_sobol_dim1_in_place(dim1);
  w = __builtin_shufflevector(w, dim1, 0, 1, 2, 3, 4, 13, 14, 7);
  laine_karras_permute_in_place(w, value_seeds);
  reverse_bits_in_place(w);
  // fraction_to_float, lane by lane: the top 24 bits fit a signed lane exactly.
  const F32x8 f = __builtin_convertvector(reinterpret_cast<I32x8>(w >> 8), F32x8) * 0x1p-24f;
  // Written straight into v: a copy through a float array cost a store and a reload per value.
  v.light_spare = f[0];
  v.light_point = {f[1], f[5]};
  v.lobe = f[2];
  v.direction = {f[3], f[6]};
  v.roulette = f[4];
}

bool owen_sobol_vertex_available() { return cpu_has_avx2(); }

}  // namespace prism
