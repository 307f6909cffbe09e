// StopSignals: while alive, the first SIGINT or SIGTERM asks a render to stop (a second one ends
// the process at once, as without prism's handler).
#pragma once

#include <atomic>

namespace prism {

class StopSignals {
 public:
  // Sets `stop` when SIGINT or SIGTERM arrives; restores the previous handlers when destroyed.
  explicit StopSignals(std::atomic<bool>& stop);
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  // The signal that arrived (SIGINT or SIGTERM), or 0.
  static int received();
  // "SIGINT", "SIGTERM" or "a signal", for messages.
  static const char* name(int signal);
};

}  // namespace prism
