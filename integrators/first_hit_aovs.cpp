#include "integrators/first_hit_aovs.h"

#include "materials/material_eval.h"

namespace prism {

void report_first_hit(const SceneDesc& desc, const SurfaceHit& hit, AovSample& aov) {
  const MaterialDesc& material = desc.material(hit.material);
  aov.hit = true;
  aov.position = hit.p;
  aov.normal = shading_normal(desc, material, hit);
  aov.albedo = base_color(desc, material, hit.uv, hit.uv_width());  // as the beauty reads it
  aov.object = hit.object;
  aov.material = hit.material >= 0 ? hit.material : static_cast<int>(desc.materials.size());
}

}  // namespace prism
