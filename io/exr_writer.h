// OpenEXR output: beauty as float or half R,G,B,A with render metadata as header attributes.
#pragma once

#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace prism {

using ExrAttribute = std::pair<std::string, std::variant<std::string, int, double>>;

// A float channel beside the beauty: one value per pixel, top row first.
struct ExrChannel {
  std::string name;
  std::vector<float> pixels;
};

// How the beauty channels (R, G, B, A) are stored; extra channels are always float.
enum class ExrPixelType { Float, Half };

// The largest finite half: values beyond it would become infinite in a half channel.
inline constexpr float kHalfMax = 65504.0f;

// What writing had to change so that the file holds only finite values.
struct ExrWriteReport {
  int nonfinite = 0;  // NaN written as 0, +-Inf as the largest float (or half)
  int clamped = 0;    // finite beauty values beyond +-65504 written as +-65504 (half only)
};

// Writes interleaved RGBA pixels (top row first), and any extra channels, to `path` through a
// temporary file and a rename. Non-finite values never reach the file, nor, in half, values a half
// cannot hold (OpenEXR's conversion would turn them into Inf). Throws OutputError naming the path
// on failure.
ExrWriteReport write_exr(const std::string& path, int width, int height, const std::vector<float>& rgba,
                         const std::vector<ExrAttribute>& attributes, const std::vector<ExrChannel>& extra = {},
                         ExrPixelType beauty = ExrPixelType::Float);

}  // namespace prism
