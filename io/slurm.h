// Talking to Slurm: batch scripts for sbatch, job ids it prints, job states scontrol reports.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace prism {

// A batch script: `#SBATCH` lines, then one command.
struct SbatchScript {
  std::string job_name;
  std::string output;                    // the log file pattern (%A array job, %a task, %j job)
  std::string directory;                 // the job's working directory
  std::vector<std::string> options;      // further sbatch options, one per line ("--mem=4G")
  std::vector<std::string> command;      // argv; "$SLURM_ARRAY_TASK_ID" is passed unquoted
};

// The script's text. Throws std::invalid_argument for an option or argument holding a newline.
std::string sbatch_script_text(const SbatchScript& script);

// `text` quoted for a POSIX shell (single quotes), unchanged when it needs none.
std::string shell_quote(const std::string& text);

// Slurm's --array list for task indices: "0-3", "1,4-6". Indices must be sorted and unique.
std::string array_spec(const std::vector<int>& indices);

// The job id `sbatch --parsable` printed ("42" or "42;cluster"), or nullopt when it printed none.
std::optional<std::string> parse_sbatch_job_id(const std::string& out);

// One job, or one array task, as `scontrol show job -o` reports it.
struct SlurmJob {
  std::string job_id;
  std::optional<int> array_task;  // set for array tasks; a pending range is expanded, one per task
  std::string state;              // PENDING, RUNNING, COMPLETED, FAILED, CANCELLED, TIMEOUT, ...
  std::string reason;             // None, Dependency, DependencyNeverSatisfied, NonZeroExitCode, ...
  std::string exit_code;          // "1:0": exit status and signal
};

// Parses `scontrol show job -o` output: one record per line of Key=Value words.
std::vector<SlurmJob> parse_scontrol_jobs(const std::string& text);

// What scontrol said about some jobs: the jobs it knows (an array job gives its tasks; jobs Slurm
// has forgotten, after MinJobAge, are absent), or why it could not say.
struct SlurmQuery {
  std::vector<SlurmJob> jobs;
  std::string error;  // "scontrol is not on PATH", or scontrol's message (the controller is down)
  bool answered() const { return error.empty(); }
};
SlurmQuery query_slurm_jobs(const std::vector<std::string>& job_ids);

}  // namespace prism
