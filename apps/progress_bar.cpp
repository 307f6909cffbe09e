#include "apps/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace prism {
namespace {

std::string clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  const auto s = static_cast<long long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%lld:%02lld:%02lld", s / 3600, (s / 60) % 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%02lld:%02lld", s / 60, s % 60);
  return buf;
}

}  // namespace

std::string ProgressBar::format(double fraction, double elapsed, int width) {
  fraction = std::clamp(fraction, 0.0, 1.0);
  const int filled = static_cast<int>(fraction * width);
  std::string bar = "[";
  for (int i = 0; i < width; ++i) bar += i < filled ? '=' : (i == filled ? '>' : ' ');
  bar += "]";
  char pct[16];
  std::snprintf(pct, sizeof pct, " %3d%%", static_cast<int>(fraction * 100.0));
  const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : -1.0;
  return bar + pct + "  " + clock_text(elapsed) + " elapsed  ETA " + (fraction >= 1.0 ? "00:00" : clock_text(eta));
}

std::optional<ProgressStyle> parse_progress_style(const std::string& text) {
  if (text == "bar") return ProgressStyle::Bar;
  if (text == "plain") return ProgressStyle::Plain;
  if (text == "none") return ProgressStyle::None;
  return std::nullopt;
}

std::string ProgressBar::plain_line(double fraction, BatchPosition batch) {
  fraction = std::clamp(fraction, 0.0, 1.0);
  char line[96];
  if (batch.count > 0)
    std::snprintf(line, sizeof line, "progress %.1f%% job %d/%d batch %.1f%%", 100.0 * fraction, batch.index + 1,
                  batch.count, 100.0 * (batch.index + fraction) / batch.count);
  else std::snprintf(line, sizeof line, "progress %.1f%%", 100.0 * fraction);
  return line;
}

ProgressBar::ProgressBar(const std::atomic<uint64_t>& done, const std::atomic<uint64_t>& total, std::string label,
                         ProgressStyle style, BatchPosition batch)
    : done_(done), total_(total), label_(std::move(label)), style_(style), batch_(batch),
      start_(std::chrono::steady_clock::now()) {
  if (style_ == ProgressStyle::Bar && ::isatty(STDERR_FILENO) != 1) style_ = ProgressStyle::None;
  if (style_ != ProgressStyle::None) thread_ = std::thread([this] { run(); });
}

ProgressBar::~ProgressBar() { stop(); }

void ProgressBar::stop() {
  {
    std::lock_guard lock(mutex_);
    if (stopped_) return;
    stopped_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) {
    thread_.join();
    draw(true);
  }
}

void ProgressBar::run() {
  const auto period = std::chrono::milliseconds(style_ == ProgressStyle::Plain ? 1000 : 200);
  std::unique_lock lock(mutex_);
  while (!stopped_) {
    lock.unlock();
    draw(false);
    lock.lock();
    wake_.wait_for(lock, period, [this] { return stopped_; });
  }
}

double ProgressBar::fraction() const {
  const uint64_t total = total_.load(std::memory_order_relaxed);
  return total ? std::min(1.0, double(done_.load(std::memory_order_relaxed)) / double(total)) : 0.0;
}

void ProgressBar::draw(bool last) {
  if (style_ == ProgressStyle::Plain) {
    // A line only when the figure changed, so a stalled render does not flood the log.
    const std::string line = plain_line(fraction(), batch_);
    if (line == last_plain_) return;
    last_plain_ = line;
    std::fprintf(stdout, "%s\n", line.c_str());
    std::fflush(stdout);
    return;
  }
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string label = label_;
  if (batch_.count > 0) label = "job " + std::to_string(batch_.index + 1) + "/" + std::to_string(batch_.count) + " " + label;
  std::fprintf(stderr, "\r%s %s", label.c_str(), format(fraction(), elapsed, 30).c_str());
  if (last) std::fputc('\n', stderr);
  std::fflush(stderr);
}

}  // namespace prism
