// ImageDesc: a decoded image's texels, kept as floats or, for 8-bit sources, as their bytes.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace prism {

struct Rgba {
  Rgb rgb;
  float a = 1.0f;
};

// The sRGB electro-optical transfer function (IEC 61966-2-1), encoded [0,1] -> linear.
float srgb_to_linear(float v);

// Linear values of the 256 codes of an 8-bit channel, exactly as decoding the channel to float
// (code x (1/255), as OpenImageIO converts) and then, for sRGB, srgb_to_linear would give them.
extern const std::array<float, 256> kSrgbCodes;
extern const std::array<float, 256> kLinearCodes;

// Texels with row 0 at the top (as images are stored), `channels` per texel (1: grey, 2: grey and
// alpha, 3: RGB, 4: RGBA). 8-bit sources keep their bytes, decoded when read: a quarter of the
// memory of floats, and four times the texels per cache line, which is what a texture lookup
// waits on. Everything else (float, half, 16-bit) is held as linear floats.
struct ImageDesc {
  std::string name;
  int width = 0, height = 0, channels = 0;
  std::vector<float> texels;   // linear, when the image is not held as bytes
  std::vector<uint8_t> bytes;  // the 8-bit codes as stored in the file, when held as bytes
  bool srgb = false;           // the bytes' colour channels are sRGB-encoded (alpha never is)

  bool holds_bytes() const { return !bytes.empty(); }
  size_t texel_count() const { return size_t(width) * size_t(height); }
  size_t memory_bytes() const { return texels.size() * sizeof(float) + bytes.size(); }

  // Starts fetching the texel at column x, row y into the cache.
  void prefetch(int x, int y) const {
    const size_t i = (size_t(y) * size_t(width) + size_t(x)) * size_t(channels);
    if (!bytes.empty())
      __builtin_prefetch(&bytes[i]);
    else
      __builtin_prefetch(&texels[i]);
  }

  // The texel at column x, row y, linear; grey is replicated to RGB, alpha is 1 without a channel.
  Rgba texel(int x, int y) const {
    const size_t i = (size_t(y) * size_t(width) + size_t(x)) * size_t(channels);
    if (!bytes.empty()) {
      const uint8_t* b = &bytes[i];
      const std::array<float, 256>& colour = srgb ? kSrgbCodes : kLinearCodes;
      switch (channels) {
        case 1: return {Rgb(colour[b[0]]), 1.0f};
        case 2: return {Rgb(colour[b[0]]), kLinearCodes[b[1]]};
        case 3: return {Rgb(colour[b[0]], colour[b[1]], colour[b[2]]), 1.0f};
        default: return {Rgb(colour[b[0]], colour[b[1]], colour[b[2]]), kLinearCodes[b[3]]};
      }
    }
    const float* t = &texels[i];
    switch (channels) {
      case 1: return {Rgb(t[0]), 1.0f};
      case 2: return {Rgb(t[0]), t[1]};
      case 3: return {Rgb(t[0], t[1], t[2]), 1.0f};
      default: return {Rgb(t[0], t[1], t[2]), t[3]};
    }
  }
};

}  // namespace prism
