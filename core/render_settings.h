// RenderSettings: everything that decides the image besides the scene and camera.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace prism {

struct RenderSettings {
  int width = 0, height = 0;   // 0 = from the camera's aspect ratio (see default_resolution)
  int spp = 64;                // samples per pixel
  int max_depth = 8;           // bounces; 0 = emitted light seen directly only
  int max_diffuse_depth = -1;  // non-delta (diffuse and glossy) bounces; -1 = no limit of its own,
                               // 0 = direct light only on such surfaces (mirrors and glass go on)
  int rr_start_depth = 3;      // Russian roulette from this bounce on
  uint64_t seed = 0;
  int tile_size = 16;
  int threads = 0;             // 0 = all hardware threads
  std::string integrator = "path";
  std::string camera;          // name or index; "" = the first in node order
};

// Settings given by a job file or on the command line; unset fields leave the settings alone.
struct RenderSettingsOverride {
  std::optional<int> width, height, spp, max_depth, max_diffuse_depth, threads;
  std::optional<uint64_t> seed;
  std::optional<std::string> camera, integrator;

  void apply_to(RenderSettings& s) const {
    if (width) s.width = *width;
    if (height) s.height = *height;
    if (spp) s.spp = *spp;
    if (max_depth) s.max_depth = *max_depth;
    if (max_diffuse_depth) s.max_diffuse_depth = *max_diffuse_depth;
    if (threads) s.threads = *threads;
    if (seed) s.seed = *seed;
    if (camera) s.camera = *camera;
    if (integrator) s.integrator = *integrator;
  }
};

}  // namespace prism
