// The `prism render` command: options as parsed from the command line, and running them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace prism {

// Command-line values; unset ones fall back to the job file, then to defaults.
struct RenderOptions {
  std::string scene;
  std::optional<std::string> output, preview, camera, integrator, resolution;
  std::optional<int> spp, max_depth, threads;
  std::optional<uint64_t> seed;
  bool quiet = false;
};

// Renders and writes the outputs; returns the process exit code and reports errors on stderr.
int run_render(const RenderOptions& options);

}  // namespace prism
