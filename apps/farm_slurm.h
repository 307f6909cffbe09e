// A farm plan and Slurm: submitting its job array and merge job, and reporting their state.
#pragma once

#include "io/farm_plan.h"

namespace prism {

// Submits the tasks whose parts are not complete as one job array, then the merge job with
// --dependency=afterok on it and --kill-on-invalid-dep=yes, and records both in the plan.
// Returns the exit code.
int submit_farm_plan(const FarmPlan& plan, bool quiet);

// Prints each task's state (Slurm's and its files'), the merge job's and the outputs'. Returns 0
// when every output is complete, kExitFarmFailed when a task or the merge failed, else
// kExitFarmPending.
int report_farm_status(const FarmPlan& plan);

}  // namespace prism
