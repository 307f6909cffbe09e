// owen_sobol_vertex: a path vertex's five Owen-scrambled Sobol draws in one pass, in AVX2 lanes.
#pragma once

#include <cstdint>

#include "core/owen_sobol.h"
#include "core/sampler.h"

namespace prism {

// Whether this CPU has AVX2, which owen_sobol_vertex needs.
bool owen_sobol_vertex_available();

// The seeds of a run of dimensions in structure-of-arrays form, as owen_sobol_vertex loads them:
// element d of each array belongs to dimension d of the run. Arrays are read eight elements at a
// time, so each holds 8 readable elements past the last dimension used.
struct SobolSeedArrays {
  const uint32_t* index;
  const uint32_t* value0;
  const uint32_t* value1;
};

// Draws 1D, 2D, 1D, 2D, 1D, the d-th with the seeds of dimension d (0 <= d < 5), into v's fields in
// their order: the very values owen_sobol_1d and owen_sobol_2d give, except that the light point
// (d = 1) is owen_sobol_2d_joint's with partner_index, the seven coordinates scrambled together in
// the lanes of one AVX2 vector. Call only where owen_sobol_vertex_available().
void owen_sobol_vertex(uint32_t reversed_index, const SobolSeedArrays& seeds, uint32_t partner_index,
                       VertexSamples& v);

}  // namespace prism
