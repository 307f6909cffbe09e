// RenderSettings: everything that decides the image besides the scene and camera.
#pragma once

#include <cstdint>
#include <string>

namespace prism {

struct RenderSettings {
  int width = 0, height = 0;   // 0 = from the camera's aspect ratio (see default_resolution)
  int spp = 64;                // samples per pixel
  int max_depth = 8;           // bounces; 0 = emitted light seen directly only
  int rr_start_depth = 3;      // Russian roulette from this bounce on
  uint64_t seed = 0;
  int tile_size = 16;
  int threads = 0;             // 0 = all hardware threads
  std::string integrator = "path";
  std::string camera;          // name or index; "" = the first in node order
};

}  // namespace prism
