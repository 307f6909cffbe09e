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

ProgressBar::ProgressBar(const std::atomic<uint64_t>& done, const std::atomic<uint64_t>& total, std::string label)
    : done_(done), total_(total), label_(std::move(label)), start_(std::chrono::steady_clock::now()),
      enabled_(::isatty(STDERR_FILENO) == 1) {
  if (enabled_) thread_ = std::thread([this] { run(); });
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
    draw();
    std::fputc('\n', stderr);
  }
}

void ProgressBar::run() {
  std::unique_lock lock(mutex_);
  while (!stopped_) {
    lock.unlock();
    draw();
    lock.lock();
    wake_.wait_for(lock, std::chrono::milliseconds(200), [this] { return stopped_; });
  }
}

void ProgressBar::draw() {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const uint64_t total = total_.load(std::memory_order_relaxed);
  const double fraction = total ? std::min(1.0, double(done_.load(std::memory_order_relaxed)) / double(total)) : 0.0;
  std::fprintf(stderr, "\r%s %s", label_.c_str(), format(fraction, elapsed, 30).c_str());
  std::fflush(stderr);
}

}  // namespace prism
