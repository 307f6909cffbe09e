// Image decoding through OpenImageIO, into linear float texels or the codes, halves or RGBE texels themselves.
#pragma once

#include <cstddef>
#include <string>

#include "core/scene_desc.h"

namespace prism {

// Auto: float images (EXR, HDR) are linear, integer ones (PNG, JPEG) sRGB-encoded.
enum class ColorSpace { Linear, Srgb, Auto };

// How texels are kept. Float: linear floats, whatever the source (ImageDesc::texels). Compact: an
// 8-bit source keeps its codes (ImageDesc::bytes, with ImageDesc::srgb saying how its colour
// channels decode), a linear half-float source its halves (ImageDesc::halves), a linear 16-bit
// source its codes (ImageDesc::words) and a linear Radiance .hdr source its RGBE texels
// (ImageDesc::rgbe, when each decodes exactly to the floats the file gives); others are floats.
enum class TexelStorage { Float, Compact };

// Decodes an encoded image (PNG, JPEG, EXR, ... sniffed from the bytes). With ColorSpace::Srgb
// the colour channels (not alpha) are converted from the sRGB transfer function to linear (or,
// kept as bytes, marked to be). Throws InputError naming `file` and `element` when the bytes do
// not decode.
ImageDesc decode_image(const unsigned char* data, size_t size, ColorSpace space, const std::string& file,
                       const std::string& element, TexelStorage storage = TexelStorage::Compact);

// Reads an image file from disk the same way, into floats unless asked otherwise.
ImageDesc read_image_file(const std::string& path, ColorSpace space, TexelStorage storage = TexelStorage::Float);

}  // namespace prism
