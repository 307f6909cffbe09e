// ExrImage: an OpenEXR image as prism writes and reads it: named channels over a data window
// inside a display window, per-channel pixel types, header attributes, compression and layout.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/pixel_window.h"

namespace prism {

// A 4x4 matrix in Imath's convention: row-major, points are row vectors (p' = p M), so the
// translation is the last row. OpenEXR's worldToCamera and worldToNDC use it.
using ExrMatrix = std::array<float, 16>;
using ExrAttribute = std::pair<std::string, std::variant<std::string, int, double, ExrMatrix>>;

enum class ExrPixelType { Half, Float, Uint };

// The largest finite half: values beyond it would become infinite in a half channel.
inline constexpr float kHalfMax = 65504.0f;

// One channel over the data window, top row first: `values` for Half and Float channels, `bits`
// for Uint channels (exact integers, e.g. the resumable film state).
struct ExrChannel {
  std::string name;  // "R", "N.X", "albedo.R": the layer is the part before the last '.'
  ExrPixelType type = ExrPixelType::Float;
  std::vector<float> values;
  std::vector<uint32_t> bits;
};

enum class ExrCompression { None, Zip, Piz, Dwaa };
// "none", "zip", "piz", "dwaa" (the --compression names); nullopt for anything else.
std::optional<ExrCompression> parse_exr_compression(const std::string& name);

struct ExrImage {
  PixelWindow display;  // the whole image; starts at (0, 0)
  PixelWindow data;     // the pixels stored: the display window, or a crop inside it
  std::vector<ExrChannel> channels;
  std::vector<ExrAttribute> attributes;
  ExrCompression compression = ExrCompression::Zip;
  // One part per layer (the unlayered channels R, G, B, A, Z form the part "rgba") instead of a
  // single-part scanline file.
  bool multipart = false;

  const ExrChannel* find(const std::string& name) const;
  const ExrAttribute* attribute(const std::string& name) const;
};

}  // namespace prism
