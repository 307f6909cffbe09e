#include "apps/farm_runner.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "apps/command_errors.h"
#include "apps/merge_command.h"
#include "apps/render_command.h"
#include "apps/render_setup.h"
#include "core/memory_limit.h"
#include "io/batch_file.h"
#include "io/exr_reader.h"
#include "io/render_identity.h"

namespace prism {

namespace {

constexpr const char* kPlanAttribute = "prism/farmPlan";
constexpr const char* kTaskAttribute = "prism/farmTask";

// A positive whole number from the environment (Slurm's SLURM_CPUS_PER_TASK, SLURM_MEM_PER_NODE).
std::optional<uint64_t> environment_number(const char* name) {
  const char* v = std::getenv(name);
  if (!v || !*v) return std::nullopt;
  char* end = nullptr;
  const unsigned long long n = std::strtoull(v, &end, 10);
  if (*end != '\0' || n == 0) return std::nullopt;
  return n;
}

}  // namespace

std::vector<BatchJobText> read_planned_jobs(const FarmPlan& plan) {
  std::vector<BatchJobText> jobs = read_job_list(plan.source);
  if (farm_source_digest(jobs) != plan.source_digest)
    throw InputError(plan.source, "", fmt::format("changed since it was planned into {}: plan it again (prism farm plan "
                                                  "... --replace), or its parts would mix two versions",
                                                  plan.directory));
  return jobs;
}

const char* farm_file_state_name(FarmFileState state) {
  switch (state) {
    case FarmFileState::Missing: return "missing";
    case FarmFileState::Complete: return "complete";
    case FarmFileState::Resumable: return "stopped";
    case FarmFileState::Foreign: return "other plan's";
  }
  return "?";
}

FarmFileState farm_file_state(const FarmPlan& plan, const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return FarmFileState::Missing;
  try {
    const ExrImage header = read_exr_header(path);
    if (attribute_text(header, kPlanAttribute) != plan.id()) return FarmFileState::Foreign;
    const std::string status = attribute_text(header, "prism/status");
    return status == "complete" ? FarmFileState::Complete : FarmFileState::Resumable;
  } catch (const InputError&) {
    return FarmFileState::Missing;  // unreadable: render it again
  }
}

FarmFileState farm_task_state(const FarmPlan& plan, size_t index) {
  for (const FarmSlice& s : plan.tasks.at(index).slices) {
    const FarmFileState state = farm_file_state(plan, s.output);
    if (state != FarmFileState::Complete) return state;
  }
  return FarmFileState::Complete;
}

int run_farm_task(const FarmPlan& plan, int index, bool quiet) {
  return run_reporting_errors([&] {
    if (index < 0 || size_t(index) >= plan.tasks.size())
      throw UsageError(fmt::format("farm task {}: the plan in {} has tasks 0 to {}", index, plan.directory, plan.tasks.size() - 1));
    const std::vector<BatchJobText> jobs = read_planned_jobs(plan);
    // Under Slurm: the CPUs and the memory the job was given.
    std::optional<uint64_t> cpus = environment_number("SLURM_CPUS_PER_TASK");
    if (!cpus) cpus = environment_number("SLURM_CPUS_ON_NODE");
    if (const std::optional<uint64_t> mb = environment_number("SLURM_MEM_PER_NODE"))
      set_memory_limit(std::min(memory_limit(), *mb << 20));

    int result = kExitOk;
    for (const FarmSlice& slice : plan.tasks[size_t(index)].slices) {
      const FarmFileState state = farm_file_state(plan, slice.output);
      if (state == FarmFileState::Complete) {
        if (!quiet) fmt::print("task {}: {} is complete already\n", index, slice.output);
        continue;
      }
      Diagnostics diag;
      JobFile job = parse_listed_job(jobs[slice.job], plan.source, diag);
      if (!quiet)
        for (const std::string& w : diag.lines()) fmt::print(stderr, "prism: warning: {} (job {}): {}\n", plan.source, jobs[slice.job].where, w);
      const bool part = slice.crop || slice.samples;
      if (part) job.preview.reset();  // the merge writes the preview of the whole image
      RenderOptions render = job_render_options(std::move(job), plan.source, jobs[slice.job].where);
      render.output = slice.output;
      if (slice.crop) render.crop = {slice.crop->x0, slice.crop->y0, slice.crop->x1, slice.crop->y1};
      if (slice.samples) render.sample_range = {slice.samples->first, slice.samples->count};
      if (cpus) render.settings.threads = int(*cpus);
      else if (plan.slurm.cpus_per_task) render.settings.threads = *plan.slurm.cpus_per_task;
      render.progress = "none";
      render.quiet = quiet;
      render.extra_attributes = {{kPlanAttribute, plan.id()}, {kTaskAttribute, std::to_string(index)}};
      if (state == FarmFileState::Resumable) {
        render.resume = slice.output;
        if (!quiet) fmt::print("task {}: continuing the stopped render {}\n", index, slice.output);
      } else if (!quiet) {
        fmt::print("task {}: {}{}{} -> {}\n", index, plan.source, plan.batch ? " " + jobs[slice.job].where : "",
                   slice.samples ? fmt::format(", samples {}..{}", slice.samples->first,
                                               slice.samples->first + slice.samples->count - 1)
                   : slice.crop ? fmt::format(", pixels {} {} {} {}", slice.crop->x0, slice.crop->y0, slice.crop->x1,
                                              slice.crop->y1)
                                : std::string(),
                   slice.output);
      }
      std::fflush(stdout);
      const int code = run_render(render);
      if (code != kExitOk && result == kExitOk) result = code;
    }
    return result;
  });
}

int run_farm_merge(const FarmPlan& plan, bool quiet) {
  return run_reporting_errors([&] {
    read_planned_jobs(plan);  // parts of an edited job must not be merged as if planned from it
    std::vector<std::string> missing;
    int result = kExitOk;
    const char* slurm_job = std::getenv("SLURM_JOB_ID");
    for (const FarmOutput& out : plan.outputs) {
      if (out.parts.empty()) {  // a frame renders in place
        if (farm_file_state(plan, out.output) != FarmFileState::Complete) missing.push_back(out.output);
        continue;
      }
      if (farm_file_state(plan, out.output) == FarmFileState::Complete) {
        if (!quiet) fmt::print("{} is merged already\n", out.output);
        continue;
      }
      bool ready = true;
      for (const std::string& part : out.parts)
        if (farm_file_state(plan, part) != FarmFileState::Complete) {
          missing.push_back(part);
          ready = false;
        }
      if (!ready) continue;
      MergeOptions merge;
      merge.parts = out.parts;
      merge.output = out.output;
      merge.preview = out.preview;
      merge.quiet = quiet;
      merge.extra_attributes = {
          {kPlanAttribute, plan.id()},
          {"prism/assembly",
           fmt::format("prism farm: {}{} in {} parts by {} (plan {}{})", plan.source, plan.batch ? " " + out.where : "",
                       out.parts.size(), farm_split_name(plan.by), plan.directory,
                       slurm_job ? fmt::format(", Slurm merge job {}", slurm_job) : std::string())}};
      const int code = run_merge(merge);
      if (code != kExitOk && result == kExitOk) result = code;
    }
    if (!missing.empty()) {
      std::string list;
      for (size_t i = 0; i < missing.size() && i < 8; ++i) list += (i ? ", " : "") + missing[i];
      if (missing.size() > 8) list += fmt::format(" and {} more", missing.size() - 8);
      throw InputError(plan.directory, "parts",
                       fmt::format("{} not complete: {} ('prism farm status {}' tells which tasks to run again)",
                                   missing.size() == 1 ? "1 file is" : fmt::format("{} files are", missing.size()), list,
                                   plan.directory));
    }
    return result;
  });
}

}  // namespace prism
