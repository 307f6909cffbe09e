#include "io/slurm.h"

#include <fmt/core.h>

#include <sstream>
#include <stdexcept>

#include "io/subprocess.h"

namespace prism {

namespace {

void refuse_newline(const std::string& text) {
  if (text.find_first_of("\n\r") != std::string::npos)
    throw std::invalid_argument("a batch script line may not hold a line break: '" + text + "'");
}

// "0-3%2" -> 0 1 2 3; "5" -> 5; "1,4-6" -> 1 4 5 6. Malformed pieces are skipped.
std::vector<int> expand_task_ids(std::string spec) {
  std::vector<int> ids;
  if (const size_t percent = spec.find('%'); percent != std::string::npos) spec.resize(percent);
  std::istringstream pieces(spec);
  std::string piece;
  while (std::getline(pieces, piece, ',')) {
    try {
      const size_t dash = piece.find('-');
      const int a = std::stoi(piece.substr(0, dash));
      const int b = dash == std::string::npos ? a : std::stoi(piece.substr(dash + 1));
      for (int i = a; i <= b && b - a < (1 << 20); ++i) ids.push_back(i);
    } catch (const std::exception&) {
    }
  }
  return ids;
}

}  // namespace

std::string shell_quote(const std::string& text) {
  if (!text.empty() && text.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./=:,+@%") ==
                           std::string::npos)
    return text;
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string sbatch_script_text(const SbatchScript& s) {
  std::string text = "#!/bin/sh\n";
  auto option = [&](const std::string& line) {
    refuse_newline(line);
    text += "#SBATCH " + line + "\n";
  };
  option("--job-name=" + s.job_name);
  option("--output=" + s.output);
  option("--chdir=" + s.directory);
  for (const std::string& o : s.options) option(o);
  std::string command = "exec";
  for (const std::string& a : s.command) {
    refuse_newline(a);
    command += " " + (a == "$SLURM_ARRAY_TASK_ID" ? a : shell_quote(a));
  }
  return text + command + "\n";
}

std::string array_spec(const std::vector<int>& indices) {
  std::string spec;
  for (size_t i = 0; i < indices.size();) {
    size_t j = i;
    while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) ++j;
    if (!spec.empty()) spec += ",";
    spec += j == i ? std::to_string(indices[i]) : fmt::format("{}-{}", indices[i], indices[j]);
    i = j + 1;
  }
  return spec;
}

std::optional<std::string> parse_sbatch_job_id(const std::string& out) {
  std::string id = out.substr(0, out.find_first_of(";\n"));
  while (!id.empty() && (id.back() == ' ' || id.back() == '\r')) id.pop_back();
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  return id;
}

std::vector<SlurmJob> parse_scontrol_jobs(const std::string& text) {
  std::vector<SlurmJob> jobs;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    SlurmJob job;
    std::string array_job, array_tasks;
    std::istringstream words(line);
    std::string word;
    while (words >> word) {
      const size_t eq = word.find('=');
      if (eq == std::string::npos) continue;
      const std::string key = word.substr(0, eq), value = word.substr(eq + 1);
      if (key == "JobId") job.job_id = value;
      else if (key == "ArrayJobId") array_job = value;
      else if (key == "ArrayTaskId") array_tasks = value;
      else if (key == "JobState") job.state = value;
      else if (key == "Reason") job.reason = value;
      else if (key == "ExitCode") job.exit_code = value;
    }
    if (job.job_id.empty() || job.state.empty()) continue;
    if (array_tasks.empty()) {
      jobs.push_back(job);
      continue;
    }
    // An array task is known by its array's id; a pending remainder lists its tasks as a range.
    job.job_id = array_job.empty() ? job.job_id : array_job;
    for (int task : expand_task_ids(array_tasks)) {
      job.array_task = task;
      jobs.push_back(job);
    }
  }
  return jobs;
}

SlurmQuery query_slurm_jobs(const std::vector<std::string>& job_ids) {
  SlurmQuery q;
  for (const std::string& id : job_ids) {
    const std::optional<CommandResult> r = run_command({"scontrol", "show", "job", "-o", id});
    if (!r) {
      q.error = "scontrol is not on PATH";
      return q;
    }
    if (r->exit_code != 0) {
      if (r->err.find("Invalid job id") != std::string::npos) continue;  // forgotten after MinJobAge
      q.error = r->message();
      if (q.error.empty()) q.error = fmt::format("scontrol exited {}", r->exit_code);
      return q;
    }
    for (SlurmJob& j : parse_scontrol_jobs(r->out)) q.jobs.push_back(std::move(j));
  }
  return q;
}

}  // namespace prism
