#include "apps/farm_slurm.h"

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include "apps/command_errors.h"
#include "apps/farm_runner.h"
#include "io/slurm.h"
#include "io/subprocess.h"

namespace prism {

namespace {

// sbatch refused a job (exit code 8, not an internal error).
class SlurmRefused : public std::runtime_error {
  using std::runtime_error::runtime_error;
};

bool slurm_running(const std::string& state) {
  static const std::set<std::string> running = {"PENDING",   "RUNNING",    "CONFIGURING", "COMPLETING", "REQUEUED",
                                                "REQUEUE_HOLD", "REQUEUE_FED", "RESIZING", "SUSPENDED", "STAGE_OUT",
                                                "SIGNALING"};
  return running.count(state) > 0;
}

const SlurmJob* find_job(const std::vector<SlurmJob>& jobs, const std::string& id, std::optional<int> task) {
  for (const SlurmJob& j : jobs)
    if (j.job_id == id && j.array_task == task) return &j;
  return nullptr;
}

// Slurm's view of a submission's array and merge jobs.
SlurmQuery query_submission(const FarmSubmission& s) {
  std::vector<std::string> ids;
  for (const std::string& id : {s.array_job, s.merge_job})
    if (!id.empty()) ids.push_back(id);
  return query_slurm_jobs(ids);
}

// The line of a task's log that says why it failed: prism's last error, else the last line.
std::string failure_line(const std::string& log) {
  std::ifstream in(log);
  std::string line, last, error;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    last = line;
    if (line.rfind("prism: error", 0) == 0 || line.rfind("prism: internal error", 0) == 0 ||
        line.rfind("slurmstepd: error", 0) == 0)
      error = line;
  }
  std::string why = error.empty() ? last : error;
  if (why.size() > 400) why = why.substr(0, 400) + "...";
  return why;
}

std::string slice_text(const FarmPlan& plan, const FarmTask& task) {
  std::string text;
  for (const FarmSlice& s : task.slices) {
    if (!text.empty()) text += "; ";
    const std::string name = std::filesystem::path(s.output).filename().string();
    if (s.samples)
      text += fmt::format("samples {}..{} -> {}", s.samples->first, s.samples->first + s.samples->count - 1, name);
    else if (s.crop)
      text += fmt::format("pixels {} {} {} {} -> {}", s.crop->x0, s.crop->y0, s.crop->x1, s.crop->y1, name);
    else
      text += (plan.batch ? plan.outputs.at(s.job).where + " -> " : std::string()) + s.output;
  }
  return text;
}

std::string submit_job(const std::vector<std::string>& argv) {
  const std::optional<CommandResult> r = run_command(argv);
  std::string command;
  for (const std::string& a : argv) command += (command.empty() ? "" : " ") + a;
  if (!r) throw UsageError(fmt::format("farm submit: cannot run '{}'", command));
  const std::optional<std::string> id = parse_sbatch_job_id(r->out);
  if (r->exit_code != 0 || !id)
    throw SlurmRefused(fmt::format("'{}' failed (exit {}): {}", command, r->exit_code, r->message()));
  return *id;
}

int submit(const FarmPlan& plan, bool quiet) {
  if (!program_on_path("sbatch"))
    throw UsageError(fmt::format(
        "farm submit: sbatch is not on PATH: run this where Slurm's commands are, or submit by hand: sbatch "
        "--array=0-{} {}, then sbatch --dependency=afterok:ARRAY_JOB --kill-on-invalid-dep=yes {}",
        plan.tasks.size() - 1, plan.task_script(), plan.merge_script()));
  // A submission still under way would render the same parts twice.
  const std::vector<FarmSubmission> earlier = read_farm_submissions(plan);
  if (!earlier.empty()) {
    const FarmSubmission& last = earlier.back();
    const SlurmQuery query = query_submission(last);
    if (!query.answered())
      throw UsageError(fmt::format("farm submit: cannot tell whether the last submission (jobs {} {}) still runs: {}",
                                   last.array_job, last.merge_job, query.error));
    bool task_failed = false;
    for (const SlurmJob& j : query.jobs) {
      if (!j.array_task) continue;
      if (slurm_running(j.state))
        throw UsageError(fmt::format("farm submit: task {} of array job {} (the last submission) is {}: wait for it, "
                                     "or scancel {} {}",
                                     *j.array_task, j.job_id, j.state, last.array_job, last.merge_job));
      task_failed = task_failed || j.state != "COMPLETED";
    }
    // A merge still waiting on a failed task can never run (Slurm cancels it soon, or never
    // without --kill-on-invalid-dep): cancel it now. One that can still run is left alone.
    if (const SlurmJob* m = find_job(query.jobs, last.merge_job, std::nullopt); m && slurm_running(m->state)) {
      if (!task_failed && m->reason != "DependencyNeverSatisfied")
        throw UsageError(fmt::format("farm submit: merge job {} of the last submission is {}: wait for it, or scancel {}",
                                     m->job_id, m->state, m->job_id));
      run_command({"scancel", m->job_id});
      if (!quiet) fmt::print("cancelled merge job {}, which waited on a failed task\n", m->job_id);
    }
  }

  std::vector<int> todo;
  for (size_t t = 0; t < plan.tasks.size(); ++t)
    if (farm_task_state(plan, t) != FarmFileState::Complete) todo.push_back(int(t));
  const bool merged = std::all_of(plan.outputs.begin(), plan.outputs.end(), [&](const FarmOutput& o) {
    return farm_file_state(plan, o.output) == FarmFileState::Complete;
  });
  if (todo.empty() && merged) {
    if (!quiet) fmt::print("nothing to submit: every output of {} is complete\n", plan.directory);
    return kExitOk;
  }
  FarmSubmission s;
  s.tasks = todo;
  if (!todo.empty()) s.array_job = submit_job({"sbatch", "--parsable", "--array=" + array_spec(todo), plan.task_script()});
  try {
    std::vector<std::string> merge = {"sbatch", "--parsable"};
    if (!s.array_job.empty()) {
      merge.push_back("--dependency=afterok:" + s.array_job);
      merge.push_back("--kill-on-invalid-dep=yes");  // a failed task cancels the merge instead of leaving it pending
    }
    merge.push_back(plan.merge_script());
    s.merge_job = submit_job(merge);
  } catch (...) {
    record_farm_submission(plan, s);  // the array runs: keep its id for status
    throw;
  }
  record_farm_submission(plan, s);
  if (!quiet) {
    if (todo.empty())
      fmt::print("every part is complete: submitted the merge as job {}\n", s.merge_job);
    else
      fmt::print("submitted {} of {} tasks ({}) as array job {}{}, and the merge as job {} after it\n", todo.size(),
                 plan.tasks.size(), array_spec(todo), s.array_job,
                 todo.size() < plan.tasks.size() ? fmt::format(" (the other {} are complete)", plan.tasks.size() - todo.size()) : "",
                 s.merge_job);
    fmt::print("'prism farm status {}' reports on them\n", plan.directory);
  }
  return kExitOk;
}

int status(const FarmPlan& plan) {
  const std::vector<FarmSubmission> submissions = read_farm_submissions(plan);
  const FarmSubmission* last = submissions.empty() ? nullptr : &submissions.back();
  const SlurmQuery view = last ? query_submission(*last) : SlurmQuery{};  // Slurm's view of it

  fmt::print("plan {}: {} by {}, {} task{}", plan.directory, plan.source, farm_split_name(plan.by), plan.tasks.size(),
             plan.tasks.size() == 1 ? "" : "s");
  if (!last) fmt::print("; not submitted ('prism farm submit {}')\n", plan.directory);
  else
    fmt::print("; submission {}: {}merge job {}{}\n", submissions.size(),
               last->array_job.empty() ? "" : fmt::format("array job {} (tasks {}), ", last->array_job, array_spec(last->tasks)),
               last->merge_job, view.answered() ? "" : fmt::format(" (Slurm's view is missing: {})", view.error));

  size_t failed = 0, done = 0;
  fmt::print("{:>5}  {:<22} {:<13} {}\n", "task", "slurm", "files", "slice");
  for (size_t t = 0; t < plan.tasks.size(); ++t) {
    const FarmFileState files = farm_task_state(plan, t);
    const bool submitted = last && !last->array_job.empty() && std::count(last->tasks.begin(), last->tasks.end(), int(t));
    std::string slurm = last && files == FarmFileState::Complete ? "(done before)" : "-";
    bool task_failed = false;
    if (submitted && view.answered()) {
      const SlurmJob* j = find_job(view.jobs, last->array_job, int(t));
      if (!j) {
        slurm = "unknown to Slurm";
        task_failed = files != FarmFileState::Complete;
      } else {
        slurm = j->state + (j->state == "FAILED" ? " exit " + j->exit_code : std::string());
        task_failed = files != FarmFileState::Complete && !slurm_running(j->state);
      }
    }
    if (files == FarmFileState::Complete) ++done;
    if (task_failed) ++failed;
    fmt::print("{:>5}  {:<22} {:<13} {}\n", t, slurm, farm_file_state_name(files), slice_text(plan, plan.tasks[t]));
    if (task_failed) {
      const std::string log = plan.task_log(last->array_job, int(t));
      const std::string why = failure_line(log);
      fmt::print("       {}\n       (log: {})\n", why.empty() ? "no log" : why, log);
    }
  }

  bool merge_failed = false, merge_running = false;
  if (last && view.answered()) {
    const SlurmJob* m = find_job(view.jobs, last->merge_job, std::nullopt);
    const std::string state = m ? m->state + (m->reason != "None" && !m->reason.empty() ? " (" + m->reason + ")" : "")
                                : std::string("unknown to Slurm");
    merge_running = m && slurm_running(m->state);
    merge_failed = !merge_running;
    fmt::print("merge job {}: {}{}\n", last->merge_job, state,
               merge_running && failed > 0 ? ", waiting on a failed task: it will not run" : "");
  }
  size_t complete = 0;
  for (const FarmOutput& o : plan.outputs) {
    const FarmFileState s = farm_file_state(plan, o.output);
    if (s == FarmFileState::Complete) ++complete;
    fmt::print("output {}: {}\n", o.output, s == FarmFileState::Complete ? "complete" : "not written");
  }
  // The merge writes each output before its preview and exits after both: complete outputs
  // while it still runs are not the end of the job.
  if (complete == plan.outputs.size() && merge_running) {
    fmt::print("{} output{} complete; merge job {} still running; not finished yet\n", complete,
               complete == 1 ? "" : "s", last->merge_job);
    return kExitFarmPending;
  }
  if (complete == plan.outputs.size()) {
    fmt::print("done: {} output{} complete\n", complete, complete == 1 ? "" : "s");
    return kExitOk;
  }
  if (failed > 0 || merge_failed) {
    fmt::print("{} of {} tasks failed{}; fix the cause and run 'prism farm submit {}' again: it keeps the {} complete "
               "part{} and runs the rest\n",
               failed, plan.tasks.size(), merge_failed ? ", and the merge did not run" : "", plan.directory, done,
               done == 1 ? "" : "s");
    return kExitFarmFailed;
  }
  fmt::print("{} of {} tasks complete; not finished yet\n", done, plan.tasks.size());
  return kExitFarmPending;
}

}  // namespace

int submit_farm_plan(const FarmPlan& plan, bool quiet) {
  return run_reporting_errors([&] {
    try {
      return submit(plan, quiet);
    } catch (const SlurmRefused& e) {
      fmt::print(stderr, "prism: error: {}\n", e.what());
      return int(kExitFarmFailed);
    }
  });
}

int report_farm_status(const FarmPlan& plan) {
  return run_reporting_errors([&] { return status(plan); });
}

}  // namespace prism
