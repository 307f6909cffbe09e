// A farm plan: one render job (or a batch) split into tasks for a cluster, kept as PLAN/plan.json
// beside the batch scripts, the part files and the record of each submission.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/pixel_window.h"
#include "core/work_split.h"
#include "io/batch_file.h"

namespace prism {

enum class FarmSplit { Frames, Tiles, Samples };

const char* farm_split_name(FarmSplit split);  // "frames", "tiles", "samples"
std::optional<FarmSplit> parse_farm_split(const std::string& text);

// One render a task runs: a job of the source, whole or a slice of it.
struct FarmSlice {
  size_t job = 0;      // index into the source's jobs (0 for a job file)
  std::string output;  // what it writes: a part file, or for frames the job's own output
  std::optional<PixelWindow> crop;
  std::optional<SampleRange> samples;
};

struct FarmTask {
  std::vector<FarmSlice> slices;
};

// A final image: a job's output, merged from parts (none for frames, which render in place).
struct FarmOutput {
  size_t job = 0;
  std::string where;  // the job's place in the source: "$" or "$.jobs[3]"
  std::string output;
  std::optional<std::string> preview;
  std::vector<std::string> parts;
};

// What every task asks of Slurm.
struct SlurmRequest {
  std::optional<int> cpus_per_task;
  std::optional<std::string> memory;      // sbatch --mem
  std::optional<std::string> time_limit;  // sbatch --time
  std::optional<std::string> partition;
  std::vector<std::string> options;       // further sbatch options, verbatim
};

struct FarmPlan {
  std::string directory;  // absolute: holds plan.json, the scripts, parts/ and logs/
  std::string source;     // absolute path of the job or batch file
  std::string source_digest;  // of the source's jobs as planned: tasks refuse a source edited since
  bool batch = false;
  FarmSplit by = FarmSplit::Samples;
  std::string prism;      // absolute path of the prism binary the tasks run
  SlurmRequest slurm;
  std::vector<FarmOutput> outputs;
  std::vector<FarmTask> tasks;

  // A digest of everything above but `directory`: parts carry it, so a part of another plan is
  // never taken for one of this plan's.
  std::string id() const;

  std::string plan_file() const;     // PLAN/plan.json
  std::string task_script() const;   // PLAN/task.sbatch
  std::string merge_script() const;  // PLAN/merge.sbatch
  std::string submissions_file() const;  // PLAN/submissions.json
  std::string parts_directory() const;   // PLAN/parts
  std::string logs_directory() const;    // PLAN/logs
  // The Slurm log of array task `task` of array job `array_job` (the task script's --output).
  std::string task_log(const std::string& array_job, int task) const;
};

// A digest of the jobs a job or batch file holds (each job's text over the batch defaults).
std::string farm_source_digest(const std::vector<BatchJobText>& jobs);

// plan.json's text (with the id, for readers; read_farm_plan recomputes it).
std::string farm_plan_json(const FarmPlan& plan);
// Reads DIRECTORY/plan.json. Throws InputError naming the file and the element.
FarmPlan read_farm_plan(const std::string& directory);

// One `prism farm submit`: the array job, the tasks it ran, and the merge job after it.
struct FarmSubmission {
  std::string array_job;  // empty when every part was complete already
  std::vector<int> tasks;
  std::string merge_job;
};

// The submissions of a plan, oldest first (none before the first submit). Throws InputError for a
// damaged file.
std::vector<FarmSubmission> read_farm_submissions(const FarmPlan& plan);
// Appends one submission to the record (written atomically).
void record_farm_submission(const FarmPlan& plan, const FarmSubmission& submission);

}  // namespace prism
