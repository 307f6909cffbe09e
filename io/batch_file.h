// Batch files: a list of render jobs, each a job file's keys over shared defaults.
#pragma once

#include <string>
#include <vector>

#include "io/diagnostics.h"
#include "io/job_file.h"

namespace prism {

struct BatchJobText {
  std::string where;  // "$.jobs[2]": where the job stands in the batch file
  std::string json;   // the job's keys merged over the defaults, as a job file's text
};

// Reads {"defaults": {...}, "jobs": [{...}, ...]} (or a bare list of jobs). Each job is the defaults
// with its own keys merged over them as an RFC 7386 merge patch: objects (materials, environment)
// merge key by key, anything else replaces, null removes a default. The jobs themselves are parsed
// one at a time by parse_job_json, so one bad job does not stop the others. Throws InputError
// naming the file for a file that is not such a list.
std::vector<BatchJobText> parse_batch_file(const std::string& path);
// The same from the file's text; `path` names it in messages.
std::vector<BatchJobText> parse_batch_json(const std::string& text, const std::string& path);

// A batch file's jobs, or a job file as a list of one job ("$"): a list or an object with "jobs"
// is a batch. `is_batch` (when given) says which it was. Throws InputError naming the file.
std::vector<BatchJobText> read_job_list(const std::string& path, bool* is_batch = nullptr);

// Parses one job of the list read from `file`; an error names the job's place in a batch
// ("batch.json: $.jobs[4]: $.spp: ...").
JobFile parse_listed_job(const BatchJobText& job, const std::string& file, Diagnostics& diag);

}  // namespace prism
