// How every prism command turns a failure into a message on stderr and an exit code.
#pragma once

#include <fmt/core.h>

#include <new>
#include <string>
#include <stdexcept>

#include "apps/exit_codes.h"
#include "core/memory_limit.h"
#include "io/errors.h"

namespace prism {

// A bad command-line argument or setting (exit code 2).
class UsageError : public std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Runs a command, mapping each class of failure to its message (printed, and kept in `message`
// when given) and exit code.
template <typename Command>
int run_reporting_errors(Command&& command, std::string* message = nullptr) {
  auto report = [&](const std::string& text, int code) {
    fmt::print(stderr, "prism: {}\n", text);
    if (message) *message = text;
    return code;
  };
  try {
    return command();
  } catch (const UsageError& e) {
    return report(std::string("error: ") + e.what(), kExitUsage);
  } catch (const InputError& e) {
    return report(std::string("error: ") + e.what(), kExitInput);
  } catch (const OutputError& e) {
    return report(std::string("error: ") + e.what(), kExitOutput);
  } catch (const MemoryLimitError& e) {
    return report(std::string("error: ") + e.what(), kExitMemory);
  } catch (const std::bad_alloc&) {
    return report("error: out of memory", kExitInternal);
  } catch (const std::exception& e) {
    return report(std::string("internal error: ") + e.what(), kExitInternal);
  }
}

}  // namespace prism
