#include "mixed_lights.h"

#include <cmath>

#include "core/sampling.h"

namespace prism {

Vec3 random_in_box(Pcg32& rng, float half) {
  return {(2 * rng.next_float() - 1) * half, (2 * rng.next_float() - 1) * half, (2 * rng.next_float() - 1) * half};
}

Vec3 random_direction(Pcg32& rng) { return sample_uniform_sphere({rng.next_float(), rng.next_float()}); }

std::vector<LightBounds> mixed_lights(Pcg32& rng, int count) {
  std::vector<LightBounds> lights(static_cast<size_t>(count));
  for (LightBounds& b : lights) {
    const Vec3 c = random_in_box(rng, 5.0f);
    b.power = std::pow(10.0, 6.0 * rng.next_float() - 3.0);
    switch (int(rng.next_float() * 4)) {
      case 0:  // a point
        b.box.extend(c);
        b.normals = DirectionCone::every_direction();
        break;
      case 1:  // a spot
        b.box.extend(c);
        b.normals = {random_direction(rng), std::cos(0.8f * rng.next_float())};
        b.cos_emit = std::cos(0.5f * rng.next_float());
        break;
      case 2:  // a sphere
        b.box.extend(c - Vec3(0.3f));
        b.box.extend(c + Vec3(0.3f));
        b.normals = DirectionCone::every_direction();
        break;
      default:  // a triangle, one- or two-sided
        b.box.extend(c);
        b.box.extend(c + random_in_box(rng, 0.5f));
        b.box.extend(c + random_in_box(rng, 0.5f));
        b.normals = {random_direction(rng), 1.0f};
        b.two_sided = rng.next_float() < 0.3f;
    }
  }
  lights[3].power = 0;  // a black light is never picked
  return lights;
}

}  // namespace prism
