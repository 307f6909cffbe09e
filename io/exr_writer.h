// OpenEXR output: an ExrImage written atomically, with only finite values and reproducible bytes.
#pragma once

#include <string>
#include <vector>

#include "io/exr_image.h"

namespace prism {

// What writing had to change so that the file holds only finite values.
struct ExrWriteReport {
  int nonfinite = 0;  // NaN written as 0, +-Inf as the largest float (or half)
  int clamped = 0;    // finite values beyond +-65504 in half channels written as +-65504
};

// Writes `image` to `path` through a temporary file in the same folder and a rename. Non-finite
// values never reach the file, nor, in half channels, values a half cannot hold (OpenEXR's
// conversion would turn them into Inf). The bytes depend only on the image: no date or host is
// recorded. Throws OutputError naming the path on failure (the earlier file, if any, is kept).
ExrWriteReport write_exr(const std::string& path, const ExrImage& image);

// The common case: interleaved RGBA (top row first) as R, G, B, A of `type`, with attributes.
ExrWriteReport write_exr(const std::string& path, int width, int height, const std::vector<float>& rgba,
                         const std::vector<ExrAttribute>& attributes, ExrPixelType type = ExrPixelType::Float);

// Interleaved RGBA as the four beauty channels of an image of that size.
std::vector<ExrChannel> rgba_channels(int width, int height, const std::vector<float>& rgba, ExrPixelType type);

}  // namespace prism
