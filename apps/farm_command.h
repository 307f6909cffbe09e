// The `prism farm` commands: split a job or batch into a Slurm job array plus a merge job (plan),
// submit it, report on it (status), and what each array task and the merge job run (task, merge).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/farm_plan.h"

namespace CLI {
class App;
}

namespace prism {

struct FarmPlanOptions {
  std::string job;                  // a job file or a batch file
  std::string by;                   // "frames", "tiles" or "samples"
  std::optional<int> parts;         // per job (tiles, samples) or in all (frames)
  std::optional<std::string> plan;  // the plan directory (default: JOB's name + ".farm")
  std::optional<std::string> prism; // the binary the tasks run (default: this one)
  SlurmRequest slurm;
  bool replace = false;             // replace a different plan in the directory
  bool quiet = false;
};

struct FarmOptions {
  FarmPlanOptions plan;
  std::string plan_directory;  // submit, status, task, merge
  int task = -1;               // task
  bool quiet = false;
};

// Adds `farm` with its subcommands; `run_farm` then runs whichever was parsed.
CLI::App* add_farm_command(CLI::App& app, FarmOptions& options);
int run_farm(const CLI::App& farm, const FarmOptions& options);

}  // namespace prism
