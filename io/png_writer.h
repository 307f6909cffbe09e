// PNG previews: linear RGB encoded with the sRGB transfer function into 8 bits.
#pragma once

#include <string>
#include <vector>

namespace prism {

// The sRGB opto-electronic transfer function (IEC 61966-2-1), linear [0,1] -> encoded.
float linear_to_srgb(float v);

// Writes interleaved RGBA float pixels as an 8-bit sRGB RGB PNG (values clipped to [0,1]),
// through a temporary file and a rename. Throws OutputError naming the path on failure.
void write_png_preview(const std::string& path, int width, int height, const std::vector<float>& rgba);

}  // namespace prism
