// A pre-scan of an OpenEXR file's headers that refuses size claims the file cannot back, before OpenEXR allocates them.
#pragma once

#include <cstdint>
#include <istream>
#include <string>

namespace prism {

// OpenEXR allocates what a header claims before it finds the file too short: a string
// attribute's declared size (up to 2 GiB, zero-filled), and a line-offset table sized by the
// data window. A corrupt or hostile file of a few hundred bytes then costs gigabytes and seconds.
// This walks the headers of the file in `in` (`file_size` bytes; OpenEXR file layout: magic,
// version and flags, then per part name/type/size/value attributes ending in a null byte) and
// throws InputError naming `path` when an attribute runs past the end of the file, a data
// window is empty or would need a line-offset table larger than the file, or the file is tiled
// or deep (prism reads only scanline images). Leaves `in` in an unspecified position.
void scan_exr_headers(std::istream& in, uint64_t file_size, const std::string& path);

}  // namespace prism
