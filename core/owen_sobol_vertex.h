// owen_sobol_vertex: a path vertex's five Owen-scrambled Sobol draws in one pass, in AVX2 lanes.
#pragma once

#include <cstdint>

#include "core/owen_sobol.h"

namespace prism {

// Whether this CPU has AVX2, which owen_sobol_vertex needs.
bool owen_sobol_vertex_available();

// Draws 1D, 2D, 1D, 2D, 1D, the d-th with seeds[d], into u: the very values owen_sobol_1d and
// owen_sobol_2d give, in that order, the seven coordinates scrambled together in the lanes of one
// AVX2 vector. Call only where owen_sobol_vertex_available().
void owen_sobol_vertex(uint32_t reversed_index, const SobolSeeds (&seeds)[5], float (&u)[7]);

}  // namespace prism
