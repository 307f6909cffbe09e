#include "apps/batch_command.h"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <vector>

#include "apps/command_errors.h"
#include "apps/render_command.h"
#include "apps/render_setup.h"
#include "apps/stop_signals.h"
#include "io/batch_file.h"
#include "io/exr_reader.h"
#include "io/job_file.h"
#include "io/render_identity.h"

namespace prism {
namespace {

// Whether `path` holds a render that finished (not a checkpoint or a stopped one).
bool complete_render_at(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  try {
    return attribute_text(read_exr_header(path), "prism/status") == "complete";
  } catch (const InputError&) {
    return false;  // unreadable: render it again
  }
}

struct JobRow {
  std::string where, scene, output;
  std::string status = "not run";
  double seconds = -1;
  std::string message;
};

const char* failure_class(int code) {
  switch (code) {
    case kExitUsage: return "usage error";
    case kExitInput: return "input error";
    case kExitOutput: return "output error";
    case kExitStopped: return "stopped";
    case kExitMemory: return "over the memory limit";
    default: return "internal error";
  }
}

int batch(const BatchOptions& o) {
  const std::vector<BatchJobText> jobs = parse_batch_file(o.file);
  if (o.progress) progress_style_option(*o.progress);  // refuse a bad style before the first job
  std::atomic<bool> stop{false};
  const StopSignals signals(stop);
  std::vector<JobRow> rows(jobs.size());
  std::map<std::string, std::string> outputs;  // output path -> the job that writes it
  int first_failure = kExitOk;
  const auto batch_start = std::chrono::steady_clock::now();

  for (size_t i = 0; i < jobs.size(); ++i) {
    JobRow& row = rows[i];
    row.where = jobs[i].where;
    if (stop.load()) continue;
    const auto start = std::chrono::steady_clock::now();
    bool skipped = false;
    const int code = run_reporting_errors(
        [&]() -> int {
          Diagnostics diag;
          JobFile job = parse_listed_job(jobs[i], o.file, diag);
          if (!o.quiet)
            for (const std::string& w : diag.lines()) fmt::print(stderr, "prism: warning: {} (job {}): {}\n", o.file, row.where, w);
          row.scene = job.scene.value_or("");
          if (!job.output) throw InputError(o.file, row.where, "no \"output\": every job of a batch names its output");
          row.output = *job.output;
          const auto [earlier, fresh] = outputs.emplace(*job.output, row.where);
          if (!fresh) throw InputError(o.file, row.where + ".output", "'" + *job.output + "' is also the output of " + earlier->second);
          if (o.skip_existing && complete_render_at(*job.output)) {
            skipped = true;
            return kExitOk;
          }
          RenderOptions render = job_render_options(std::move(job), o.file, row.where);
          render.quiet = o.quiet;
          render.strict = o.strict;
          render.progress = o.progress;
          if (o.threads) render.settings.threads = *o.threads;
          if (!o.quiet) fmt::print("job {}/{} ({}): {} -> {}\n", i + 1, jobs.size(), row.where, render.scene, row.output);
          std::fflush(stdout);
          return run_render(render, BatchContext{&stop, BatchPosition{int(i), int(jobs.size())}}, &row.message);
        },
        &row.message);
    row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    row.status = skipped ? "skipped" : code == kExitOk ? "ok" : failure_class(code);
    if (code != kExitOk && code != kExitStopped && first_failure == kExitOk) first_failure = code;
  }

  const size_t ok = size_t(std::count_if(rows.begin(), rows.end(), [](const JobRow& r) { return r.status == "ok"; }));
  const size_t skipped = size_t(std::count_if(rows.begin(), rows.end(), [](const JobRow& r) { return r.status == "skipped"; }));
  const size_t not_run = size_t(std::count_if(rows.begin(), rows.end(), [](const JobRow& r) { return r.status == "not run"; }));
  const size_t failed = rows.size() - ok - skipped - not_run;
  if (!o.quiet || failed > 0 || stop.load()) {
    // The summary: one row per job, the reason under each failure.
    fmt::print("\n{:>4}  {:<14} {:>9}  {:<32} {}\n", "job", "status", "seconds", "output", "scene");
    for (size_t i = 0; i < rows.size(); ++i) {
      const JobRow& r = rows[i];
      fmt::print("{:>4}  {:<14} {:>9}  {:<32} {}\n", i + 1, r.status, r.seconds < 0 ? "-" : fmt::format("{:.2f}", r.seconds),
                 r.output.empty() ? "-" : r.output, r.scene.empty() ? "-" : r.scene);
      if (!r.message.empty()) fmt::print("      {}\n", r.message);
    }
    fmt::print("{} jobs: {} rendered, {} skipped, {} failed{}, {:.1f} s\n", rows.size(), ok, skipped, failed,
               not_run ? fmt::format(", {} not run", not_run) : std::string(),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - batch_start).count());
  }
  if (stop.load()) {
    fmt::print(stderr, "prism: batch stopped by {}; the job under way wrote what it had (continue it with --resume)\n",
               StopSignals::name(StopSignals::received()));
    return kExitStopped;
  }
  return first_failure;
}

}  // namespace

CLI::App* add_batch_command(CLI::App& app, BatchOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "batch", "Render a list of jobs: {\"defaults\": {job keys}, \"jobs\": [{job keys}, ...]}; goes on past a failing "
               "job, prints a summary, exits non-zero when any failed");
  cmd->add_option("JOBS", o.file, "The batch file (JSON; each job takes the keys of a job file, over the defaults)")
      ->required();
  cmd->add_flag("--skip-existing", o.skip_existing,
                "Skip jobs whose output is already a complete render (not a checkpoint or a stopped one)");
  cmd->add_option("--progress", o.progress,
                  "Progress: bar (default; on a terminal, with the job's and the batch's share), plain ('progress 42.0% "
                  "job 2/5 batch 28.4%' lines on stdout) or none");
  cmd->add_option("--threads", o.threads, "Worker threads for every job; 0 = all cores")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--strict", o.strict, "Refuse missing or undecodable textures in every job (default: magenta)");
  cmd->add_flag("-q,--quiet", o.quiet, "Print nothing but errors and, when a job failed, the summary");
  return cmd;
}

int run_batch(const BatchOptions& options) {
  return run_reporting_errors([&] { return batch(options); });
}

}  // namespace prism
