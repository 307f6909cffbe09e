// Batch files: a list of render jobs, each a job file's keys over shared defaults.
#pragma once

#include <string>
#include <vector>

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

}  // namespace prism
