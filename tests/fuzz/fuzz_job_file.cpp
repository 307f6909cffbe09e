// libFuzzer target: the job-file and batch-file parsers on arbitrary text. Bad text must give an
// InputError (naming the key) and nothing else.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_limits.h"
#include "io/batch_file.h"
#include "io/errors.h"
#include "io/job_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prism::fuzz::set_fuzz_limits();
  const std::string text(reinterpret_cast<const char*>(data), size);
  prism::Diagnostics diag;
  try {
    prism::parse_job_json(text, "fuzz.json", diag);
  } catch (const prism::InputError&) {
  }
  try {
    for (const auto& job : prism::parse_batch_json(text, "fuzz-batch.json")) {
      try {
        prism::parse_job_json(job.json, "fuzz-batch.json " + job.where, diag);
      } catch (const prism::InputError&) {
      }
    }
  } catch (const prism::InputError&) {
  }
  return 0;
}
