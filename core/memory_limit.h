// The memory ceiling prism plans within (--memory-limit): footprints are estimated and checked before allocating.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

namespace prism {

// The process-wide limit in bytes. Until set_memory_limit is called it is the default below.
uint64_t memory_limit();
void set_memory_limit(uint64_t bytes);

// The default: the memory the system reports available when prism starts (MemAvailable, or the
// physical memory where /proc/meminfo is missing), so a scene that cannot fit is refused with an
// estimate instead of being killed by the kernel half-way through.
uint64_t default_memory_limit();

// An estimate exceeded the memory limit: the message names what needs it and both sizes.
class MemoryLimitError : public std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws MemoryLimitError when `estimate` bytes for `what` ("file.gltf: image 3") exceed the limit.
void require_memory(uint64_t estimate, const std::string& what);

// Estimates accumulate here so that the sum of a scene's parts is checked, not each alone.
class MemoryTally {
 public:
  // Adds `estimate` bytes for `what`; throws MemoryLimitError when the total exceeds the limit.
  void add(uint64_t estimate, const std::string& what);
  uint64_t total() const { return total_; }

 private:
  uint64_t total_ = 0;
};

// "1.5 GiB", "640 MiB", "12 KiB", "100 bytes".
std::string format_bytes(uint64_t bytes);

// Parses "8G", "512M", "64k", "1.5GiB" or a plain byte count; nullopt when malformed or zero.
std::optional<uint64_t> parse_byte_size(const std::string& text);

}  // namespace prism
