// How every prism command turns a failure into a message on stderr and an exit code.
#pragma once

#include <fmt/core.h>

#include <new>
#include <stdexcept>

#include "apps/exit_codes.h"
#include "io/errors.h"

namespace prism {

// A bad command-line argument or setting (exit code 2).
class UsageError : public std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Runs a command, mapping each class of failure to its message and exit code.
template <typename Command>
int run_reporting_errors(Command&& command) {
  try {
    return command();
  } catch (const UsageError& e) {
    fmt::print(stderr, "prism: error: {}\n", e.what());
    return kExitUsage;
  } catch (const InputError& e) {
    fmt::print(stderr, "prism: error: {}\n", e.what());
    return kExitInput;
  } catch (const OutputError& e) {
    fmt::print(stderr, "prism: error: {}\n", e.what());
    return kExitOutput;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "prism: error: out of memory\n");
    return kExitInternal;
  } catch (const std::exception& e) {
    fmt::print(stderr, "prism: internal error: {}\n", e.what());
    return kExitInternal;
  }
}

}  // namespace prism
