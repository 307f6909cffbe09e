#include "core/memory_limit.h"

#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace prism {
namespace {

std::atomic<uint64_t> g_limit{0};  // 0: not set yet, use the default

}  // namespace

uint64_t default_memory_limit() {
  static const uint64_t value = [] {
    std::ifstream meminfo("/proc/meminfo");
    std::string key, unit;
    uint64_t kib = 0;
    while (meminfo >> key >> kib >> unit)
      if (key == "MemAvailable:") return kib * 1024;
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : UINT64_MAX;
  }();
  return value;
}

uint64_t memory_limit() {
  const uint64_t set = g_limit.load(std::memory_order_relaxed);
  return set ? set : default_memory_limit();
}

void set_memory_limit(uint64_t bytes) { g_limit.store(bytes, std::memory_order_relaxed); }

void require_memory(uint64_t estimate, const std::string& what) {
  const uint64_t limit = memory_limit();
  if (estimate > limit)
    throw MemoryLimitError(what + " needs about " + format_bytes(estimate) + ", more than the memory limit of " +
                           format_bytes(limit) + " (--memory-limit)");
}

void MemoryTally::add(uint64_t estimate, const std::string& what) {
  total_ = estimate > UINT64_MAX - total_ ? UINT64_MAX : total_ + estimate;
  if (total_ > memory_limit())
    throw MemoryLimitError(what + " brings the estimate to about " + format_bytes(total_) +
                           ", more than the memory limit of " + format_bytes(memory_limit()) + " (--memory-limit)");
}

std::string format_bytes(uint64_t bytes) {
  const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  if (bytes < 1024) return std::to_string(bytes) + " bytes";
  double v = double(bytes) / 1024;
  int u = 0;
  while (v >= 1024 && u < 5) v /= 1024, ++u;
  char text[32];
  std::snprintf(text, sizeof text, v < 10 ? "%.1f %s" : "%.0f %s", v, units[u]);
  return text;
}

std::optional<uint64_t> parse_byte_size(const std::string& text) {
  std::istringstream in(text);
  double value = 0;
  if (!(in >> value) || !(value > 0) || !std::isfinite(value)) return std::nullopt;
  std::string unit;
  in >> unit;
  if (in.rdbuf()->in_avail() > 0) return std::nullopt;
  for (char& c : unit) c = char(std::tolower(static_cast<unsigned char>(c)));
  double scale = 1;
  if (unit.empty() || unit == "b") scale = 1;
  else if (unit == "k" || unit == "kb" || unit == "kib") scale = 1024.0;
  else if (unit == "m" || unit == "mb" || unit == "mib") scale = 1024.0 * 1024;
  else if (unit == "g" || unit == "gb" || unit == "gib") scale = 1024.0 * 1024 * 1024;
  else if (unit == "t" || unit == "tb" || unit == "tib") scale = 1024.0 * 1024 * 1024 * 1024;
  else return std::nullopt;
  const double bytes = value * scale;
  if (bytes < 1 || bytes >= 1.8e19) return std::nullopt;
  return uint64_t(bytes);
}

}  // namespace prism
