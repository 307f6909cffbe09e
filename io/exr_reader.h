// OpenEXR input for merge, resume and tests: every channel of a single- or multi-part scanline
// file, with its windows and the attributes prism writes.
#pragma once

#include <string>
#include <vector>

#include "io/exr_image.h"

namespace prism {

// Reads `path` whole: half channels widen to float, uint channels keep their bits; string, int,
// float, double and 4x4 float matrix attributes are kept (from the first part). Every part must
// share the data window. Throws InputError naming the file for anything unreadable.
ExrImage read_exr(const std::string& path);
// The same without the pixels: windows, attributes, and channels with names and types only.
ExrImage read_exr_header(const std::string& path);
// read_exr from the bytes of a file already in memory; `name` names it in messages.
ExrImage read_exr_from_memory(const std::vector<unsigned char>& bytes, const std::string& name);

}  // namespace prism
