// ProgressBar: a terminal progress line with percentage, elapsed time and ETA, redrawn by its own thread.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace prism {

class ProgressBar {
 public:
  // Reads `done` out of `total` work units (an estimate that may change) until stop(); draws on
  // stderr only when it is a terminal.
  ProgressBar(const std::atomic<uint64_t>& done, const std::atomic<uint64_t>& total, std::string label);
  ~ProgressBar();
  void stop();  // draws the final state and ends the line

  // "[=====>    ]  42%  00:12 elapsed  ETA 00:16" for a fraction and elapsed seconds.
  static std::string format(double fraction, double elapsed_seconds, int width);

 private:
  void run();
  void draw();

  const std::atomic<uint64_t>& done_;
  const std::atomic<uint64_t>& total_;
  std::string label_;
  std::chrono::steady_clock::time_point start_;
  bool enabled_;
  bool stopped_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

}  // namespace prism
