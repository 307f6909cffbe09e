// SurfaceParams: the glTF material model evaluated at one surface point (factors x textures).
#pragma once

#include "core/vec3.h"

namespace prism {

struct SurfaceParams {
  Rgb base_color{1, 1, 1};
  float metallic = 0;
  float roughness = 1;
  float transmission = 0;
  float ior = 1.5f;
  float specular = 1;         // KHR_materials_specular weight of the dielectric layer
  Rgb specular_color{1, 1, 1};  // and the tint of its F0
  bool thin_walled = true;  // transmission passes straight through a sheet (no volume)
};

}  // namespace prism
