#include "apps/farm_planner.h"

#include <fmt/core.h>

#include <filesystem>
#include <set>

#include "apps/command_errors.h"
#include "apps/render_setup.h"
#include "io/atomic_file.h"
#include "io/batch_file.h"
#include "io/slurm.h"

namespace prism {

namespace fs = std::filesystem;

namespace {

std::string absolute_path(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

// The options every job of the plan asks of Slurm, as sbatch lines.
std::vector<std::string> sbatch_options(const SlurmRequest& r, bool with_cpus) {
  std::vector<std::string> lines;
  if (with_cpus && r.cpus_per_task) lines.push_back(fmt::format("--cpus-per-task={}", *r.cpus_per_task));
  if (r.memory) lines.push_back("--mem=" + *r.memory);
  if (r.time_limit) lines.push_back("--time=" + *r.time_limit);
  if (r.partition) lines.push_back("--partition=" + *r.partition);
  for (const std::string& o : r.options) lines.push_back(o);
  return lines;
}

// The settings a split needs (image size, spp, budgets), resolved as `prism render` would.
RenderSettings job_settings(const JobFile& job, const std::string& source, const std::string& where) {
  RenderOptions render = job_render_options(job, source, where);
  render.quiet = true;  // the job's warnings were printed when it was parsed
  return prepare_render(render).settings;
}

std::string part_name(const FarmPlan& plan, size_t job, size_t part) {
  return plan.batch ? fmt::format("job{:04}-part{:03}.exr", job, part) : fmt::format("part{:03}.exr", part);
}

}  // namespace

FarmPlan make_farm_plan(const FarmPlanOptions& o) {
  const std::optional<FarmSplit> by = parse_farm_split(o.by);
  if (!by) throw UsageError("farm plan --by: expected frames, tiles or samples, got '" + o.by + "'");
  if (o.parts && *o.parts < 1) throw UsageError("farm plan --parts: expected 1 or more");
  if (*by != FarmSplit::Frames && !o.parts) throw UsageError("farm plan --by " + o.by + ": give --parts N (parts per job)");

  const std::string extension = fs::path(o.job).extension().string();
  if (extension == ".gltf" || extension == ".glb")
    throw UsageError(fmt::format("farm plan {}: give a job file or a batch file (JSON naming the scene, its output and "
                                 "settings), e.g. {{\"scene\": \"{}\", \"output\": \"{}.exr\", \"spp\": 256}}",
                                 o.job, fs::path(o.job).filename().string(), fs::path(o.job).stem().string()));
  FarmPlan plan;
  plan.source = absolute_path(o.job);
  const std::vector<BatchJobText> jobs = read_job_list(plan.source, &plan.batch);
  plan.source_digest = farm_source_digest(jobs);
  plan.by = *by;
  const std::string stem = fs::path(o.job).stem().string();
  plan.directory = absolute_path(o.plan ? *o.plan : stem + ".farm");
  plan.prism = o.prism ? absolute_path(*o.prism) : fs::read_symlink("/proc/self/exe").string();
  plan.slurm = o.slurm;

  std::set<std::string> outputs;
  std::vector<JobFile> parsed;
  for (const BatchJobText& text : jobs) {
    Diagnostics diag;
    JobFile job = parse_listed_job(text, plan.source, diag);
    if (!o.quiet)
      for (const std::string& w : diag.lines()) fmt::print(stderr, "prism: warning: {} (job {}): {}\n", plan.source, text.where, w);
    if (!job.output)
      throw InputError(o.job, text.where, "no \"output\": a farm job names its output (relative to the job file)");
    if (!outputs.insert(*job.output).second)
      throw InputError(o.job, text.where + ".output", "'" + *job.output + "' is also the output of another job");
    parsed.push_back(std::move(job));
  }

  if (plan.by == FarmSplit::Frames) {
    const int parts = o.parts.value_or(int(jobs.size()));
    if (size_t(parts) > jobs.size())
      throw UsageError(fmt::format("farm plan --by frames --parts {}: {} has only {} job(s), one per frame", parts, o.job,
                                   jobs.size()));
    for (size_t i = 0; i < jobs.size(); ++i)
      plan.outputs.push_back({i, jobs[i].where, *parsed[i].output, parsed[i].preview, {}});
    for (const std::vector<size_t>& group : split_frames(jobs.size(), parts)) {
      FarmTask& task = plan.tasks.emplace_back();
      for (size_t i : group) task.slices.push_back({i, *parsed[i].output, std::nullopt, std::nullopt});
    }
    return plan;
  }

  for (size_t i = 0; i < jobs.size(); ++i) {
    const std::string where = jobs[i].where;
    const RenderSettings s = job_settings(parsed[i], plan.source, where);
    if (s.crop != PixelWindow{} || parsed[i].settings.first_sample)
      throw UsageError(fmt::format("farm plan: {} {} is a slice already (\"crop\" or \"sample_range\"): plan the whole job",
                                   o.job, where));
    if (s.counts_follow_the_render())
      throw UsageError(fmt::format(
          "farm plan --by {}: {} {} has a {}, whose samples depend on the machine and on the whole image; "
          "split it by frames, or give it a fixed \"spp\" shared uniformly",
          o.by, o.job, where,
          s.time_budget > 0 ? "time budget" : s.noise_target > 0 ? "noise budget" : "sample allocation by error"));
    FarmOutput& out = plan.outputs.emplace_back();
    out = {i, where, *parsed[i].output, parsed[i].preview, {}};
    std::vector<std::optional<PixelWindow>> crops;
    std::vector<std::optional<SampleRange>> ranges;
    if (plan.by == FarmSplit::Samples) {
      if (uint64_t(*o.parts) > uint64_t(s.spp))
        throw UsageError(fmt::format("farm plan --by samples --parts {}: {} {} has only {} spp", *o.parts, o.job, where, s.spp));
      for (const SampleRange& r : split_samples(uint64_t(s.spp), *o.parts)) ranges.push_back(r);
      crops.resize(ranges.size());
    } else {
      for (const PixelWindow& w : split_tiles(s.width, s.height, *o.parts)) crops.push_back(w);
      if (crops.empty())
        throw UsageError(fmt::format("farm plan --by tiles --parts {}: no grid of {} tiles fits the {}x{} image of {} {}",
                                     *o.parts, *o.parts, s.width, s.height, o.job, where));
      ranges.resize(crops.size());
    }
    for (size_t k = 0; k < crops.size(); ++k) {
      const std::string part = (fs::path(plan.directory) / "parts" / part_name(plan, i, k)).string();
      out.parts.push_back(part);
      plan.tasks.push_back(FarmTask{{FarmSlice{i, part, crops[k], ranges[k]}}});
    }
  }
  return plan;
}

void write_farm_plan(const FarmPlan& plan, bool replace) {
  std::error_code ec;
  if (fs::exists(plan.plan_file(), ec)) {
    std::string existing;
    try {
      existing = read_farm_plan(plan.directory).id();
    } catch (const InputError&) {
      existing = "unreadable";
    }
    if (existing != plan.id()) {
      if (!replace)
        throw UsageError(fmt::format("farm plan: {} holds a different plan ({}); pass --replace to replace it (its parts "
                                     "are rendered again), or choose another --plan directory",
                                     plan.directory, existing));
      fs::remove(plan.submissions_file(), ec);  // its jobs belong to the old plan
    }
  }
  for (const std::string& dir : {plan.directory, plan.parts_directory(), plan.logs_directory()}) {
    fs::create_directories(dir, ec);
    if (ec) throw OutputError(dir, "cannot create the plan directory: " + ec.message());
  }
  write_file_atomically(plan.plan_file(), farm_plan_json(plan));

  const std::string name = "prism-" + fs::path(plan.source).stem().string();
  SbatchScript task;
  task.job_name = name;
  task.output = (fs::path(plan.logs_directory()) / "task-%A_%a.log").string();
  task.directory = plan.directory;
  task.options = sbatch_options(plan.slurm, true);
  task.command = {plan.prism, "farm", "task", plan.directory, "$SLURM_ARRAY_TASK_ID"};
  SbatchScript merge;
  merge.job_name = name + "-merge";
  merge.output = (fs::path(plan.logs_directory()) / "merge-%j.log").string();
  merge.directory = plan.directory;
  merge.options = sbatch_options(plan.slurm, false);
  merge.command = {plan.prism, "farm", "merge", plan.directory};
  try {
    write_file_atomically(plan.task_script(), sbatch_script_text(task));
    write_file_atomically(plan.merge_script(), sbatch_script_text(merge));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("farm plan: ") + e.what());
  }
}

}  // namespace prism
