#include "io/image_codecs.h"

#include <dlfcn.h>

#include <filesystem>
#include <stdexcept>
#include <vector>

namespace prism {
namespace {

constexpr const char* kModuleName = "libprism_image_codecs.so";

// Beside the running binary first (build/bin, or wherever prism was copied with it), then where
// this build put it (test binaries live in other folders).
std::vector<std::string> module_candidates() {
  std::vector<std::string> paths;
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) paths.push_back((self.parent_path() / kModuleName).string());
#ifdef PRISM_IMAGE_CODECS_MODULE
  // Held in an array of a fixed size, so that the build folder's name does not move the constants
  // laid out after it: two builds of the same source in folders whose paths differ in length timed
  // 4% apart on the Cornell box (likely 4K aliasing between a hot constant and a hot stack slot in
  // one layout and not the other; unconfirmed, no performance counters), which no A/B comparison
  // of two builds should measure (docs/PERFORMANCE.md, session 40).
  static constexpr char kBuildModule[4096] = PRISM_IMAGE_CODECS_MODULE;
  if (paths.empty() || paths.front() != kBuildModule) paths.push_back(kBuildModule);
#endif
  return paths;
}

// Tries each candidate in turn; `error` collects why each one failed.
const ImageCodecs* open_module(std::string& error) {
  const auto failed = [&](const std::string& why) { error += (error.empty() ? "" : "; ") + why; };
  for (const std::string& path : module_candidates()) {
    if (!std::filesystem::exists(path)) {
      failed(path + ": not found");
      continue;
    }
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed: it lives as long as prism
    if (!handle) {
      const char* why = dlerror();
      failed(why ? why : path + ": cannot be opened");
      continue;
    }
    using Entry = const ImageCodecs* (*)();
    if (const auto entry = reinterpret_cast<Entry>(dlsym(handle, "prism_image_codecs_v4"))) return entry();
    failed(path + ": has no prism_image_codecs_v4");
  }
  return nullptr;
}

}  // namespace

const ImageCodecs& image_codecs() {
  static std::string error;
  static const ImageCodecs* const codecs = open_module(error);
  if (!codecs)
    throw std::runtime_error("cannot open prism's image codecs (OpenImageIO), which reading images and writing PNG "
                             "need: " + error);
  return *codecs;
}

}  // namespace prism
