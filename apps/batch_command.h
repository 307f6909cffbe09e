// The `prism batch` command: renders a list of jobs, going on past failures, with a summary table.
#pragma once

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace prism {

struct BatchOptions {
  std::string file;
  bool skip_existing = false;           // skip jobs whose output is a complete render already
  std::optional<std::string> progress;  // "bar", "plain" or "none"
  std::optional<int> threads;
  bool quiet = false;
  bool strict = false;  // --strict for every job
};

CLI::App* add_batch_command(CLI::App& app, BatchOptions& options);

// Renders every job; returns 0 when all succeeded (or were skipped), kExitStopped when a signal
// stopped the batch, else the exit code of the first job that failed.
int run_batch(const BatchOptions& options);

}  // namespace prism
