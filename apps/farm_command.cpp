#include "apps/farm_command.h"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "apps/command_errors.h"
#include "apps/farm_planner.h"
#include "apps/farm_runner.h"
#include "apps/farm_slurm.h"
#include "io/slurm.h"

namespace prism {

namespace {

int plan_command(const FarmPlanOptions& o) {
  return run_reporting_errors([&] {
    const FarmPlan plan = make_farm_plan(o);
    write_farm_plan(plan, o.replace);
    if (!o.quiet) {
      fmt::print("plan {}: {} tasks by {} of {} ({} output{})\n", plan.directory, plan.tasks.size(),
                 farm_split_name(plan.by), plan.source, plan.outputs.size(), plan.outputs.size() == 1 ? "" : "s");
      fmt::print("submit with:  prism farm submit {}\n", plan.directory);
      fmt::print("or by hand:   sbatch --array=0-{} {}\n", plan.tasks.size() - 1, plan.task_script());
      fmt::print("              sbatch --dependency=afterok:ARRAY_JOB_ID --kill-on-invalid-dep=yes {}\n", plan.merge_script());
      fmt::print("follow with:  prism farm status {}\n", plan.directory);
    }
    return kExitOk;
  });
}

// Runs `command` on the plan read from `directory`, reporting a plan that cannot be read.
template <typename Command>
int with_plan(const std::string& directory, Command&& command) {
  std::optional<FarmPlan> plan;
  const int code = run_reporting_errors([&] {
    plan = read_farm_plan(directory);
    return kExitOk;
  });
  return plan ? command(*plan) : code;
}

}  // namespace

CLI::App* add_farm_command(CLI::App& app, FarmOptions& o) {
  CLI::App* farm = app.add_subcommand(
      "farm", "Render on a Slurm cluster: plan a job or batch as a job array and a merge job, submit it, follow it "
              "(docs/FARM.md)");
  farm->require_subcommand(1);

  CLI::App* plan = farm->add_subcommand(
      "plan", "Split a job file or batch file into tasks and write PLAN/plan.json with the Slurm batch scripts "
              "PLAN/task.sbatch (the job array) and PLAN/merge.sbatch");
  FarmPlanOptions& p = o.plan;
  plan->add_option("JOB", p.job, "A job file, or a batch file (JSON): every job names its \"output\"")->required();
  plan->add_option("--by", p.by,
                   "How to split: samples (each task renders a slice of every pixel's samples), tiles (each task a "
                   "rectangle of the image), frames (each task whole jobs of a batch)")
      ->required()
      ->check(CLI::IsMember({"frames", "tiles", "samples"}));
  plan->add_option("--parts", p.parts,
                   "Tasks per job for samples and tiles; tasks in all for frames (default: one per job)")
      ->check(CLI::PositiveNumber);
  plan->add_option("--plan", p.plan, "The plan directory, on storage every node sees (default: JOB's name + .farm)");
  plan->add_option("--prism", p.prism, "The prism binary the tasks run, as the nodes see it (default: this one)");
  plan->add_option("--cpus-per-task", p.slurm.cpus_per_task,
                   "CPUs each task asks for (sbatch --cpus-per-task); the task renders with that many threads")
      ->check(CLI::PositiveNumber);
  plan->add_option("--mem", p.slurm.memory,
                   "Memory each task asks for (sbatch --mem, e.g. 8G); the task then refuses work that would exceed it");
  plan->add_option("--time-limit", p.slurm.time_limit,
                   "Time limit of each task (sbatch --time, e.g. 2:00:00); a task stopped at its limit keeps its samples "
                   "and continues when submitted again");
  plan->add_option("--partition", p.slurm.partition, "Slurm partition (sbatch --partition)");
  plan->add_option("--sbatch-option", p.slurm.options,
                   "Any further sbatch option for the tasks and the merge, e.g. --sbatch-option=--account=vfx (repeatable)");
  plan->add_flag("--replace", p.replace, "Replace a different plan in the plan directory (its parts are rendered again)");
  plan->add_flag("-q,--quiet", p.quiet, "Print nothing but errors");

  CLI::App* submit = farm->add_subcommand(
      "submit", "Submit the plan's unfinished tasks as one job array and the merge job after it (afterok, "
                "--kill-on-invalid-dep=yes); run it again after a failure to retry only what is missing");
  submit->add_option("PLAN", o.plan_directory, "The plan directory")->required();
  submit->add_flag("-q,--quiet", o.quiet, "Print nothing but errors");

  CLI::App* status = farm->add_subcommand(
      "status", "Report each task's Slurm state and part file, the merge job and the outputs. Exit status 0 when every "
                "output is complete, 8 when a task or the merge failed, 9 while unfinished");
  status->add_option("PLAN", o.plan_directory, "The plan directory")->required();

  CLI::App* task = farm->add_subcommand(
      "task", "Run task INDEX of a plan (what each array task runs): renders its slices to their part files, "
              "skipping complete ones and continuing stopped ones");
  task->add_option("PLAN", o.plan_directory, "The plan directory")->required();
  task->add_option("INDEX", o.task, "The task (SLURM_ARRAY_TASK_ID)")->required()->check(CLI::NonNegativeNumber);
  task->add_flag("-q,--quiet", o.quiet, "Print nothing but errors");

  CLI::App* merge = farm->add_subcommand(
      "merge", "Merge the plan's parts into its outputs (what the merge job runs); refuses while a part is missing");
  merge->add_option("PLAN", o.plan_directory, "The plan directory")->required();
  merge->add_flag("-q,--quiet", o.quiet, "Print nothing but errors");
  return farm;
}

int run_farm(const CLI::App& farm, const FarmOptions& o) {
  const auto parsed = [&](const char* name) { return farm.get_subcommand(name)->parsed(); };
  if (parsed("plan")) return plan_command(o.plan);
  if (parsed("submit")) return with_plan(o.plan_directory, [&](const FarmPlan& p) { return submit_farm_plan(p, o.quiet); });
  if (parsed("status")) return with_plan(o.plan_directory, [&](const FarmPlan& p) { return report_farm_status(p); });
  if (parsed("task")) return with_plan(o.plan_directory, [&](const FarmPlan& p) { return run_farm_task(p, o.task, o.quiet); });
  if (parsed("merge")) return with_plan(o.plan_directory, [&](const FarmPlan& p) { return run_farm_merge(p, o.quiet); });
  return kExitUsage;
}

}  // namespace prism
