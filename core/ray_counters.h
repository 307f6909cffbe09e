// RayCounters: rays traced by kind, kept per tile and summed, for Mrays/s figures.
#pragma once

#include <cstdint>

namespace prism {

struct RayCounters {
  uint64_t camera = 0;     // primary rays
  uint64_t extension = 0;  // rays continuing a path after a bounce
  uint64_t shadow = 0;     // occlusion rays for next-event estimation

  uint64_t total() const { return camera + extension + shadow; }
  RayCounters& operator+=(const RayCounters& o) {
    camera += o.camera;
    extension += o.extension;
    shadow += o.shadow;
    return *this;
  }
};

}  // namespace prism
