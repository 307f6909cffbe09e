// Planning a farm render: the job or batch split into tasks, written as a plan directory with its
// Slurm batch scripts.
#pragma once

#include "apps/farm_command.h"
#include "io/farm_plan.h"

namespace prism {

// Reads the jobs, resolves their settings and splits them as asked. Throws UsageError for a split
// that cannot be made (more parts than samples, a time budget split by samples) and InputError for
// bad jobs.
FarmPlan make_farm_plan(const FarmPlanOptions& options);

// Creates the plan directory (with parts/ and logs/) and writes plan.json, task.sbatch and
// merge.sbatch. A directory that holds a different plan is refused unless `replace`.
void write_farm_plan(const FarmPlan& plan, bool replace);

}  // namespace prism
