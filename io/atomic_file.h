// AtomicFile: write to a temporary file beside the target, then rename, so no reader ever sees half a file.
#pragma once

#include <string>

namespace prism {

// Throws OutputError if `target` could not be written by AtomicFile (missing directory, a
// directory in its place, a directory that is not writable): lets a long render fail early.
void check_output_path(const std::string& target);

// Writes `contents` to `target` through an AtomicFile; throws OutputError naming it on failure.
void write_file_atomically(const std::string& target, const std::string& contents);

class AtomicFile {
 public:
  // Checks that the target's directory exists and that the target is not a directory; throws
  // OutputError otherwise. Nothing is created until the caller writes temp_path().
  explicit AtomicFile(const std::string& target);
  ~AtomicFile();  // removes the temporary file unless commit() succeeded
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& temp_path() const { return temp_; }
  const std::string& target() const { return target_; }
  // Renames the temporary file onto the target; throws OutputError on failure.
  void commit();

 private:
  std::string target_, temp_;
  bool committed_ = false;
};

}  // namespace prism
