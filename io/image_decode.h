// Image decoding through OpenImageIO from memory, into linear float texels.
#pragma once

#include <cstddef>
#include <string>

#include "core/scene_desc.h"

namespace prism {

// Auto: float images (EXR, HDR) are linear, integer ones (PNG, JPEG) sRGB-encoded.
enum class ColorSpace { Linear, Srgb, Auto };

// Decodes an encoded image (PNG, JPEG, EXR, ... sniffed from the bytes). With ColorSpace::Srgb
// the colour channels (not alpha) are converted from the sRGB transfer function to linear.
// Throws InputError naming `file` and `element` when the bytes do not decode.
ImageDesc decode_image(const unsigned char* data, size_t size, ColorSpace space, const std::string& file,
                       const std::string& element);

// Reads an image file from disk the same way.
ImageDesc read_image_file(const std::string& path, ColorSpace space);

// The sRGB electro-optical transfer function (IEC 61966-2-1), encoded [0,1] -> linear.
float srgb_to_linear(float v);

}  // namespace prism
