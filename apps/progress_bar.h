// ProgressBar: progress of a render (and of its batch) as a terminal bar or as plain lines for farm
// managers, redrawn by its own thread.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace prism {

enum class ProgressStyle {
  Bar,    // a redrawn line on stderr, only when stderr is a terminal
  Plain,  // "progress 42.0%" lines on stdout, at most one a second
  None,
};
// "bar", "plain" or "none"; nullopt for anything else.
std::optional<ProgressStyle> parse_progress_style(const std::string& text);

// Where a render stands in a batch: job `index` (from 0) of `count`, each counted as an equal share.
struct BatchPosition {
  int index = 0;
  int count = 0;
};

class ProgressBar {
 public:
  // Reads `done` out of `total` work units (an estimate that may change) until stop().
  ProgressBar(const std::atomic<uint64_t>& done, const std::atomic<uint64_t>& total, std::string label,
              ProgressStyle style = ProgressStyle::Bar, BatchPosition batch = {});
  ~ProgressBar();
  void stop();  // draws the final state and ends the line

  // "[=====>    ]  42%  00:12 elapsed  ETA 00:16" for a fraction and elapsed seconds.
  static std::string format(double fraction, double elapsed_seconds, int width);
  // "progress 42.0%", with " job 2/5 batch 28.4%" inside a batch.
  static std::string plain_line(double fraction, BatchPosition batch);

 private:
  void run();
  void draw(bool last);
  double fraction() const;

  const std::atomic<uint64_t>& done_;
  const std::atomic<uint64_t>& total_;
  std::string label_;
  ProgressStyle style_;
  BatchPosition batch_;
  std::chrono::steady_clock::time_point start_;
  std::string last_plain_;
  bool stopped_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

}  // namespace prism
