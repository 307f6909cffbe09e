// Error types that name the file, the element and the reason; apps map each class to an exit code.
#pragma once

#include <stdexcept>
#include <string>

namespace prism {

// The user's input (scene, job file, image) is wrong: message is "file: element: reason".
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& element, const std::string& reason)
      : std::runtime_error(file + ": " + (element.empty() ? "" : element + ": ") + reason), reason_(reason) {}
  const std::string& reason() const { return reason_; }

 private:
  std::string reason_;
};

// An output could not be written: message names the path and the reason.
class OutputError : public std::runtime_error {
 public:
  OutputError(const std::string& path, const std::string& reason) : std::runtime_error(path + ": " + reason) {}
};

}  // namespace prism
