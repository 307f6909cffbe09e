// The `prism render` command: options as parsed from the command line, and running them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/render_settings.h"

namespace prism {

// Command-line values; unset ones fall back to the job file, then to defaults.
struct RenderOptions {
  std::string scene;
  std::optional<std::string> output, preview;
  std::optional<std::string> pixel_type;   // "float" or "half" for the beauty channels
  std::optional<std::string> compression;  // "zip", "piz", "dwaa", "none"
  bool multipart = false;
  std::optional<std::string> aovs;         // "albedo,normal,..."
  std::vector<int> crop;                   // x0 y0 x1 y1
  std::vector<uint64_t> sample_range;      // first count
  std::optional<std::string> resolution;  // "WxH", parsed into settings
  std::optional<std::string> time;        // "30s", "2m", parsed into settings
  RenderSettingsOverride settings;
  std::optional<std::string> env;  // a map path, or "R,G,B" / "V" for a constant sky
  std::optional<float> env_intensity, env_rotation;
  bool quiet = false;
};

// Renders and writes the outputs; returns the process exit code and reports errors on stderr.
int run_render(const RenderOptions& options);

}  // namespace prism
