// The `prism compare` command: error metrics between an image and a reference, for people and scripts.
#pragma once

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace prism {

struct CompareOptions {
  std::string test, reference;
  std::string metric = "relmse";
  std::optional<double> threshold;
  std::optional<std::string> diff;  // false-colour PNG, or the raw error as an EXR
  std::optional<float> diff_max;
  bool quiet = false;
};

// Declares the command and its options on `app`, filling `options` when parsed.
CLI::App* add_compare_command(CLI::App& app, CompareOptions& options);

// Prints the metrics; returns kExitThreshold when the metric misses --threshold.
int run_compare(const CompareOptions& options);

}  // namespace prism
