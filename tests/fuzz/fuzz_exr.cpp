// libFuzzer target: the EXR reader that merge, compare and resume use, on arbitrary bytes, then
// the film state of the image read. Bad files must give an InputError or MemoryLimitError.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_limits.h"
#include "io/errors.h"
#include "io/exr_reader.h"
#include "io/film_state.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prism::fuzz::set_fuzz_limits();
  const std::vector<unsigned char> bytes(data, data + size);
  try {
    const prism::ExrImage image = prism::read_exr_from_memory(bytes, "fuzz.exr");
    if (prism::has_film_state(image)) prism::film_from_image(image, "fuzz.exr");
  } catch (const prism::InputError&) {
  } catch (const prism::MemoryLimitError&) {
  }
  return 0;
}
