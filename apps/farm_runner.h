// What runs on the cluster: one array task of a farm plan (its slices, skipping finished ones and
// continuing stopped ones) and the merge job; and the state of the files they write.
#pragma once

#include <string>
#include <vector>

#include "io/batch_file.h"
#include "io/farm_plan.h"

namespace prism {

// The plan's source, read again; throws InputError when it no longer holds the jobs planned.
std::vector<BatchJobText> read_planned_jobs(const FarmPlan& plan);

enum class FarmFileState {
  Missing,    // not there (or unreadable)
  Complete,   // a finished render of this plan
  Resumable,  // a stopped or checkpointed render of this plan: the task continues it
  Foreign,    // a render, but not of this plan (an older plan's, or not a farm part)
};

const char* farm_file_state_name(FarmFileState state);  // "missing", "complete", ...

// The state of a part or output file, judged by its header.
FarmFileState farm_file_state(const FarmPlan& plan, const std::string& path);

// The state of task `index`: Complete when all its slices are, else the first that is not.
FarmFileState farm_task_state(const FarmPlan& plan, size_t index);

// Renders the slices of task `index` that are not complete; returns the exit code (the first
// failure's, after trying every slice).
int run_farm_task(const FarmPlan& plan, int index, bool quiet);

// Merges every output whose parts are all complete (skipping outputs merged already); checks
// frames. Returns the exit code: kExitInput naming the parts missing.
int run_farm_merge(const FarmPlan& plan, bool quiet);

}  // namespace prism
