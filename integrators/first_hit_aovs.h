// The AOVs both integrators report from a camera ray's first hit: position, normal, albedo, ids.
#pragma once

#include "core/aov.h"
#include "core/scene_desc.h"
#include "core/surface_hit.h"

namespace prism {

// Fills the first-hit fields of `aov`: the (normal-mapped) shading normal, the base colour as
// albedo, the object, and the material (the default material as index desc.materials.size()).
void report_first_hit(const SceneDesc& desc, const SurfaceHit& hit, AovSample& aov);

}  // namespace prism
