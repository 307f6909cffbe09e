// The `prism merge` command: combines partial renders (sample slices and crops) into one image.
#pragma once

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace prism {

struct MergeOptions {
  std::vector<std::string> parts;
  std::string output;
  bool quiet = false;
};

CLI::App* add_merge_command(CLI::App& app, MergeOptions& options);

// Merges the parts and writes the output; returns the process exit code.
int run_merge(const MergeOptions& options);

}  // namespace prism
