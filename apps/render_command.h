// The `prism render` command: options as parsed from the command line, and running them.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "apps/progress_bar.h"
#include "core/render_settings.h"
#include "io/job_file.h"

namespace prism {

// Command-line values; unset ones fall back to the job file, then to defaults.
struct RenderOptions {
  std::string scene;
  std::optional<JobFile> job;  // a job parsed already (from a batch): used instead of reading `scene`
  std::optional<std::string> output, preview;
  std::optional<std::string> pixel_type;   // "float" or "half" for the beauty channels
  std::optional<std::string> compression;  // "zip", "piz", "dwaa", "none"
  bool multipart = false;
  bool stamp = false;                      // date and render time in the header
  std::optional<std::string> aovs;         // "albedo,normal,..."
  std::vector<int> crop;                   // x0 y0 x1 y1
  std::vector<uint64_t> sample_range;      // first count
  std::optional<std::string> resolution;  // "WxH", parsed into settings
  std::optional<std::string> time;        // "30s", "2m", parsed into settings
  std::optional<std::string> checkpoint;  // "60", "5m": how often to write the progressive image
  std::optional<std::string> resume;      // a stopped render's EXR to continue
  std::optional<std::string> progress;    // "bar", "plain" or "none"
  RenderSettingsOverride settings;
  std::optional<std::string> env;  // a map path, or "R,G,B" / "V" for a constant sky
  std::optional<float> env_intensity, env_rotation;
  bool quiet = false;
  bool strict = false;  // missing or undecodable textures are errors, not magenta
  // Written into the header as they are (prism farm: the plan and the task a part belongs to).
  std::vector<std::pair<std::string, std::string>> extra_attributes;
};

// How a render runs inside a batch: the batch's stop flag (set by its signal handler) and where
// the render stands in it.
struct BatchContext {
  std::atomic<bool>* stop = nullptr;
  BatchPosition position;
};

// Renders and writes the outputs; returns the process exit code and reports errors on stderr.
// Without a batch, SIGINT and SIGTERM stop the render, which writes what it has (resumable) and
// returns kExitStopped. A failure's message is also kept in `message` when given.
int run_render(const RenderOptions& options, const BatchContext& batch = {}, std::string* message = nullptr);

}  // namespace prism
