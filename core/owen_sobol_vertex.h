// owen_sobol_vertex: a path vertex's five Owen-scrambled Sobol draws in one pass, eight lanes wide.
#pragma once

#include <cstdint>

#include "core/owen_sobol.h"

namespace prism {

// Draws 1D, 2D, 1D, 2D, 1D, the d-th with seeds[d], into u: the very values owen_sobol_1d and
// owen_sobol_2d give, in that order. On CPUs with AVX2 the seven coordinates are scrambled
// together in the lanes of one vector; elsewhere one by one.
void owen_sobol_vertex(uint32_t reversed_index, const SobolSeeds (&seeds)[5], float (&u)[7]);

// Whether owen_sobol_vertex takes the vector path on this CPU.
bool owen_sobol_vertex_vectorized();

}  // namespace prism
