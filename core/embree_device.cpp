#include "core/embree_device.h"

#include <mutex>
#include <stdexcept>

namespace prism {
namespace {

std::mutex g_error_mutex;
std::string g_last_error;

void record_error(void*, RTCError code, const char* message) {
  std::lock_guard lock(g_error_mutex);
  g_last_error = "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "");
}

}  // namespace

RTCDevice embree_device() {
  static RTCDevice device = [] {
    RTCDevice d = rtcNewDevice(nullptr);
    if (!d) throw std::runtime_error("cannot create the Embree device (error " +
                                     std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
    rtcSetDeviceErrorFunction(d, record_error, nullptr);
    return d;
  }();
  return device;
}

void throw_on_embree_error(const std::string& what) {
  std::lock_guard lock(g_error_mutex);
  if (g_last_error.empty()) return;
  std::string message = what + ": " + g_last_error;
  g_last_error.clear();
  throw std::runtime_error(message);
}

}  // namespace prism
