// The `prism merge` command: combines partial renders (sample slices and crops) into one image.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace CLI {
class App;
}

namespace prism {

struct MergeOptions {
  std::vector<std::string> parts;
  std::string output;
  std::optional<std::string> preview;  // an 8-bit sRGB PNG of the merged image
  bool quiet = false;
  // Written into the merged header as they are (prism farm: how the image was assembled).
  std::vector<std::pair<std::string, std::string>> extra_attributes;
};

CLI::App* add_merge_command(CLI::App& app, MergeOptions& options);

// Merges the parts and writes the output; returns the process exit code.
int run_merge(const MergeOptions& options);

}  // namespace prism
