// portal_views: EnvironmentPortals::view for eight shading points at once, in SIMD lanes.
#pragma once

#include "core/environment_portals.h"
#include "core/vec3.h"

namespace prism {

// out[k] = portals.view(refs[k]) for k < n (n <= 8), bit for bit: each corner seen from each point
// and each triangle's solid angle, in AVX2 where the CPU has it and `avx2` allows it, else in SSE
// pairs. out's views are default-constructed ones, which this fills.
void portal_views(const EnvironmentPortals& portals, const Vec3* refs, int n, EnvironmentPortals::View* out,
                  bool avx2 = true);

}  // namespace prism
