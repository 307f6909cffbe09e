#include "io/batch_file.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

#include "io/errors.h"
#include "io/json_parse.h"

namespace prism {

namespace {

std::string file_text(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", std::string("cannot open the ") + what);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::vector<BatchJobText> parse_batch_file(const std::string& path) {
  return parse_batch_json(file_text(path, "batch file"), path);
}

std::vector<BatchJobText> read_job_list(const std::string& path, bool* is_batch) {
  const std::string text = file_text(path, "job or batch file");
  const nlohmann::json root = parse_json(text, path);
  const bool batch = root.is_array() || (root.is_object() && root.contains("jobs"));
  if (is_batch) *is_batch = batch;
  if (batch) return parse_batch_json(text, path);
  if (!root.is_object()) throw InputError(path, "$", "expected a job (an object of job keys) or a batch");
  return {BatchJobText{"$", text}};
}

std::vector<BatchJobText> parse_batch_json(const std::string& text, const std::string& path) {
  const nlohmann::json root = parse_json(text, path);
  nlohmann::json defaults = nlohmann::json::object(), jobs;
  if (root.is_array()) {
    jobs = root;
  } else if (root.is_object()) {
    for (const auto& [key, value] : root.items())
      if (key != "defaults" && key != "jobs")
        throw InputError(path, "$." + key, "unknown key: a batch file has \"defaults\" and \"jobs\"");
    if (root.contains("defaults")) defaults = root["defaults"];
    if (!defaults.is_object()) throw InputError(path, "$.defaults", "expected an object of job keys");
    if (!root.contains("jobs")) throw InputError(path, "$.jobs", "missing: expected a list of jobs");
    jobs = root["jobs"];
  }
  if (!jobs.is_array()) throw InputError(path, "$.jobs", "expected a list of jobs");
  if (jobs.empty()) throw InputError(path, "$.jobs", "the batch has no jobs");
  std::vector<BatchJobText> out;
  for (size_t i = 0; i < jobs.size(); ++i) {
    const std::string where = (root.is_array() ? "$[" : "$.jobs[") + std::to_string(i) + "]";
    if (!jobs[i].is_object()) throw InputError(path, where, "expected an object of job keys");
    nlohmann::json job = defaults;
    job.merge_patch(jobs[i]);
    out.push_back({where, job.dump()});
  }
  return out;
}

JobFile parse_listed_job(const BatchJobText& job, const std::string& file, Diagnostics& diag) {
  try {
    return parse_job_json(job.json, file, diag);
  } catch (const InputError& e) {
    if (job.where == "$") throw;
    // "batch.json: $.spp: ..." -> "batch.json: $.jobs[4]: $.spp: ..." (the job over the defaults)
    std::string reason = e.what();
    if (reason.rfind(file + ": ", 0) == 0) reason.erase(0, file.size() + 2);
    throw InputError(file, job.where, reason);
  }
}

}  // namespace prism
