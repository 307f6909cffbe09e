// Running another program (Slurm's sbatch, scontrol) and capturing what it prints.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace prism {

struct CommandResult {
  int exit_code = -1;  // the exit status, or 128 + the signal that ended it
  std::string out, err;
  // What it said, for an error message: stderr (stdout when stderr is empty), without the
  // trailing newline.
  std::string message() const;
};

// Runs argv[0] (looked up on PATH) with the arguments, stdin from /dev/null, and waits for it.
// Returns nullopt when the program cannot be started (not installed); never throws for its failure.
std::optional<CommandResult> run_command(const std::vector<std::string>& argv);

// Whether `program` is an executable on PATH (or a path to one).
bool program_on_path(const std::string& program);

}  // namespace prism
