// libFuzzer target: glTF and GLB bytes through prism's loader, with no file system. A clean
// InputError or MemoryLimitError is the expected outcome for a bad file; anything else (a
// crash, a sanitizer report, another exception) is a bug.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_limits.h"
#include "io/errors.h"
#include "io/gltf_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prism::fuzz::set_fuzz_limits();
  const std::vector<unsigned char> bytes(data, data + size);
  prism::Diagnostics diag;
  try {
    prism::load_gltf_from_memory(bytes, "", "fuzz.gltf", diag);
  } catch (const prism::InputError&) {
  } catch (const prism::MemoryLimitError&) {
  }
  return 0;
}
