#include "io/batch_file.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

#include "io/errors.h"
#include "io/json_parse.h"

namespace prism {

std::vector<BatchJobText> parse_batch_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the batch file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_batch_json(text.str(), path);
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

}  // namespace prism
