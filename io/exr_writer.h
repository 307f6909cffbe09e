// OpenEXR output: beauty as float R,G,B,A with render metadata as header attributes.
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

// Writes interleaved RGBA float pixels (top row first), and any extra channels, to `path` through
// a temporary file and a rename. Non-finite values never reach the file: NaN becomes 0 and +-Inf the largest float;
// the number replaced is returned. Throws OutputError naming the path on failure.
int write_exr(const std::string& path, int width, int height, const std::vector<float>& rgba,
              const std::vector<ExrAttribute>& attributes, const std::vector<ExrChannel>& extra = {});

}  // namespace prism
