#include "io/farm_plan.h"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/atomic_file.h"
#include "io/errors.h"
#include "io/json_parse.h"

namespace prism {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr int kPlanVersion = 1;

json window_json(const PixelWindow& w) { return json::array({w.x0, w.y0, w.x1, w.y1}); }

// Everything that decides what the tasks render, in a fixed order: the text the id digests.
json plan_body(const FarmPlan& p) {
  json j;
  j["version"] = kPlanVersion;
  j["source"] = p.source;
  j["source_digest"] = p.source_digest;
  j["batch"] = p.batch;
  j["by"] = farm_split_name(p.by);
  j["prism"] = p.prism;
  json slurm = json::object();
  if (p.slurm.cpus_per_task) slurm["cpus_per_task"] = *p.slurm.cpus_per_task;
  if (p.slurm.memory) slurm["memory"] = *p.slurm.memory;
  if (p.slurm.time_limit) slurm["time_limit"] = *p.slurm.time_limit;
  if (p.slurm.partition) slurm["partition"] = *p.slurm.partition;
  slurm["options"] = p.slurm.options;
  j["slurm"] = slurm;
  json outputs = json::array();
  for (const FarmOutput& o : p.outputs) {
    json e{{"job", o.job}, {"where", o.where}, {"output", o.output}, {"parts", o.parts}};
    if (o.preview) e["preview"] = *o.preview;
    outputs.push_back(e);
  }
  j["outputs"] = outputs;
  json tasks = json::array();
  for (const FarmTask& t : p.tasks) {
    json slices = json::array();
    for (const FarmSlice& s : t.slices) {
      json e{{"job", s.job}, {"output", s.output}};
      if (s.crop) e["crop"] = window_json(*s.crop);
      if (s.samples) e["sample_range"] = json::array({s.samples->first, s.samples->count});
      slices.push_back(e);
    }
    tasks.push_back(json{{"slices", slices}});
  }
  j["tasks"] = tasks;
  return j;
}

// Typed access to plan.json with errors that name the file and the element.
class PlanReader {
 public:
  explicit PlanReader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& reason) const {
    throw InputError(file_, where, reason + " (plan.json is written by 'prism farm plan': plan again)");
  }
  const json& at(const json& j, const std::string& key, const std::string& where) const {
    if (!j.is_object() || !j.contains(key)) fail(where + "." + key, "missing");
    return j.at(key);
  }
  std::string text(const json& j, const std::string& key, const std::string& where) const {
    const json& v = at(j, key, where);
    if (!v.is_string()) fail(where + "." + key, "expected a string");
    return v.get<std::string>();
  }
  uint64_t number(const json& j, const std::string& key, const std::string& where) const {
    const json& v = at(j, key, where);
    if (!v.is_number_unsigned()) fail(where + "." + key, "expected a whole number of 0 or more");
    return v.get<uint64_t>();
  }
  const json& list(const json& j, const std::string& key, const std::string& where) const {
    const json& v = at(j, key, where);
    if (!v.is_array()) fail(where + "." + key, "expected a list");
    return v;
  }
  std::vector<uint64_t> numbers(const json& v, size_t n, const std::string& where) const {
    if (!v.is_array() || v.size() != n) fail(where, fmt::format("expected a list of {} numbers", n));
    std::vector<uint64_t> out;
    for (const json& e : v) {
      if (!e.is_number_unsigned() || e.get<uint64_t>() > (uint64_t(1) << 40)) fail(where, "expected whole numbers");
      out.push_back(e.get<uint64_t>());
    }
    return out;
  }

 private:
  std::string file_;
};

// FNV-1a, 64 bits: a stable digest of the plan's text on every platform.
uint64_t fnv1a(const std::string& text) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : text) h = (h ^ c) * 0x100000001b3ull;
  return h;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

const char* farm_split_name(FarmSplit split) {
  switch (split) {
    case FarmSplit::Frames: return "frames";
    case FarmSplit::Tiles: return "tiles";
    case FarmSplit::Samples: return "samples";
  }
  return "?";
}

std::optional<FarmSplit> parse_farm_split(const std::string& text) {
  for (FarmSplit s : {FarmSplit::Frames, FarmSplit::Tiles, FarmSplit::Samples})
    if (text == farm_split_name(s)) return s;
  return std::nullopt;
}

std::string farm_source_digest(const std::vector<BatchJobText>& jobs) {
  std::string all;
  for (const BatchJobText& j : jobs) all += std::to_string(j.json.size()) + ":" + j.json;
  return fmt::format("{:016x}", fnv1a(all));
}

std::string FarmPlan::id() const { return fmt::format("{:016x}", fnv1a(plan_body(*this).dump())); }
std::string FarmPlan::plan_file() const { return (fs::path(directory) / "plan.json").string(); }
std::string FarmPlan::task_script() const { return (fs::path(directory) / "task.sbatch").string(); }
std::string FarmPlan::merge_script() const { return (fs::path(directory) / "merge.sbatch").string(); }
std::string FarmPlan::submissions_file() const { return (fs::path(directory) / "submissions.json").string(); }
std::string FarmPlan::parts_directory() const { return (fs::path(directory) / "parts").string(); }
std::string FarmPlan::logs_directory() const { return (fs::path(directory) / "logs").string(); }
std::string FarmPlan::task_log(const std::string& array_job, int task) const {
  return (fs::path(logs_directory()) / fmt::format("task-{}_{}.log", array_job, task)).string();
}

std::string farm_plan_json(const FarmPlan& plan) {
  json j = plan_body(plan);
  j["id"] = plan.id();
  return j.dump(2) + "\n";
}

FarmPlan read_farm_plan(const std::string& directory) {
  FarmPlan p;
  p.directory = fs::absolute(directory).lexically_normal().string();
  const std::string file = p.plan_file();
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw InputError(directory, "plan.json", "missing: not a plan directory (make one with 'prism farm plan')");
  const PlanReader r(file);
  const json j = parse_json(slurp(file), file);
  if (!j.is_object()) r.fail("$", "expected an object");
  if (r.number(j, "version", "$") != kPlanVersion)
    r.fail("$.version", fmt::format("this prism reads plans of version {}", kPlanVersion));
  p.source = r.text(j, "source", "$");
  p.source_digest = r.text(j, "source_digest", "$");
  const json& batch = r.at(j, "batch", "$");
  if (!batch.is_boolean()) r.fail("$.batch", "expected true or false");
  p.batch = batch.get<bool>();
  const std::optional<FarmSplit> by = parse_farm_split(r.text(j, "by", "$"));
  if (!by) r.fail("$.by", "expected frames, tiles or samples");
  p.by = *by;
  p.prism = r.text(j, "prism", "$");
  const json& slurm = r.at(j, "slurm", "$");
  if (!slurm.is_object()) r.fail("$.slurm", "expected an object");
  if (slurm.contains("cpus_per_task")) p.slurm.cpus_per_task = int(r.number(slurm, "cpus_per_task", "$.slurm"));
  if (slurm.contains("memory")) p.slurm.memory = r.text(slurm, "memory", "$.slurm");
  if (slurm.contains("time_limit")) p.slurm.time_limit = r.text(slurm, "time_limit", "$.slurm");
  if (slurm.contains("partition")) p.slurm.partition = r.text(slurm, "partition", "$.slurm");
  const json& options = r.list(slurm, "options", "$.slurm");
  for (size_t i = 0; i < options.size(); ++i) {
    if (!options[i].is_string()) r.fail(fmt::format("$.slurm.options[{}]", i), "expected a string");
    p.slurm.options.push_back(options[i].get<std::string>());
  }
  const json& outputs = r.list(j, "outputs", "$");
  for (size_t i = 0; i < outputs.size(); ++i) {
    const std::string where = fmt::format("$.outputs[{}]", i);
    FarmOutput o;
    o.job = size_t(r.number(outputs[i], "job", where));
    o.where = r.text(outputs[i], "where", where);
    o.output = r.text(outputs[i], "output", where);
    if (outputs[i].contains("preview")) o.preview = r.text(outputs[i], "preview", where);
    const json& parts = r.list(outputs[i], "parts", where);
    for (size_t k = 0; k < parts.size(); ++k) {
      if (!parts[k].is_string()) r.fail(fmt::format("{}.parts[{}]", where, k), "expected a string");
      o.parts.push_back(parts[k].get<std::string>());
    }
    p.outputs.push_back(std::move(o));
  }
  const json& tasks = r.list(j, "tasks", "$");
  if (tasks.empty()) r.fail("$.tasks", "the plan has no tasks");
  for (size_t t = 0; t < tasks.size(); ++t) {
    FarmTask task;
    const std::string where = fmt::format("$.tasks[{}]", t);
    const json& slices = r.list(tasks[t], "slices", where);
    for (size_t k = 0; k < slices.size(); ++k) {
      const std::string at = fmt::format("{}.slices[{}]", where, k);
      FarmSlice s;
      s.job = size_t(r.number(slices[k], "job", at));
      s.output = r.text(slices[k], "output", at);
      if (slices[k].contains("crop")) {
        const std::vector<uint64_t> c = r.numbers(slices[k]["crop"], 4, at + ".crop");
        s.crop = PixelWindow{int(c[0]), int(c[1]), int(c[2]), int(c[3])};
      }
      if (slices[k].contains("sample_range")) {
        const std::vector<uint64_t> c = r.numbers(slices[k]["sample_range"], 2, at + ".sample_range");
        s.samples = SampleRange{c[0], c[1]};
      }
      task.slices.push_back(std::move(s));
    }
    p.tasks.push_back(std::move(task));
  }
  for (size_t t = 0; t < p.tasks.size(); ++t)
    for (size_t k = 0; k < p.tasks[t].slices.size(); ++k)
      if (p.tasks[t].slices[k].job >= p.outputs.size())
        r.fail(fmt::format("$.tasks[{}].slices[{}].job", t, k), "is not a job of the plan's outputs");
  if (r.text(j, "id", "$") != p.id()) r.fail("$.id", "does not match the plan's contents: plan.json was edited by hand");
  return p;
}

std::vector<FarmSubmission> read_farm_submissions(const FarmPlan& plan) {
  const std::string file = plan.submissions_file();
  std::error_code ec;
  if (!fs::exists(file, ec)) return {};
  const PlanReader r(file);
  const json j = parse_json(slurp(file), file);
  if (!j.is_array()) r.fail("$", "expected a list of submissions");
  std::vector<FarmSubmission> out;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string where = fmt::format("$[{}]", i);
    FarmSubmission s;
    s.array_job = r.text(j[i], "array_job", where);
    s.merge_job = r.text(j[i], "merge_job", where);
    const json& tasks = r.list(j[i], "tasks", where);
    for (const json& t : tasks) {
      if (!t.is_number_unsigned()) r.fail(where + ".tasks", "expected task indices");
      s.tasks.push_back(t.get<int>());
    }
    out.push_back(std::move(s));
  }
  return out;
}

void record_farm_submission(const FarmPlan& plan, const FarmSubmission& submission) {
  json list = json::array();
  for (const FarmSubmission& s : read_farm_submissions(plan))
    list.push_back(json{{"array_job", s.array_job}, {"tasks", s.tasks}, {"merge_job", s.merge_job}});
  list.push_back(json{{"array_job", submission.array_job}, {"tasks", submission.tasks}, {"merge_job", submission.merge_job}});
  write_file_atomically(plan.submissions_file(), list.dump(2) + "\n");
}

}  // namespace prism
