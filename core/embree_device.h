// The process-wide Embree device, created once with an error callback that records the last error.
#pragma once

#include <embree3/rtcore.h>

#include <string>

namespace prism {

RTCDevice embree_device();
// Throws std::runtime_error with Embree's message if an error was recorded since the last call.
void throw_on_embree_error(const std::string& what);

}  // namespace prism
