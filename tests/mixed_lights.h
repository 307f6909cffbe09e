// Random light bounds for the light tree's tests: points, spots, spheres and triangles.
#pragma once

#include <vector>

#include "core/light_bounds.h"
#include "core/pcg32.h"
#include "core/vec3.h"

namespace prism {

// A point in the cube [-half, half]^3.
Vec3 random_in_box(Pcg32& rng, float half);
// A unit direction, uniform on the sphere.
Vec3 random_direction(Pcg32& rng);
// Triangles of every orientation, points, spots and spheres, with powers over six decades; light 3
// has no power.
std::vector<LightBounds> mixed_lights(Pcg32& rng, int count);

}  // namespace prism
