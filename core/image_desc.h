// ImageDesc: a decoded image's texels, kept as floats or as the 8- or 16-bit codes, half floats or RGBE texels they came in.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/rgbe.h"
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

// The float an IEEE 754 binary16 value stands for (every half is exactly a float), NaN payloads
// kept. Subnormals are scaled from an integer, so the result does not depend on whether the CPU
// flushes float subnormals.
inline float half_to_float(uint16_t h) {
  const uint32_t sign = uint32_t(h & 0x8000u) << 16;
  const uint32_t magnitude = h & 0x7fffu;  // exponent and mantissa
  uint32_t bits;
  if (magnitude >= 0x7c00u)  // infinity or NaN
    bits = 0x7f800000u | ((magnitude & 0x3ffu) << 13);
  else if (magnitude >= 0x0400u)  // normal: the exponent rebiased from 15 to 127
    bits = (magnitude << 13) + (uint32_t(127 - 15) << 23);
  else  // zero or subnormal: mantissa x 2^-24
    bits = std::bit_cast<uint32_t>(float(magnitude) * 0x1p-24f);
  return std::bit_cast<float>(bits | sign);
}

// Texels with row 0 at the top (as images are stored), `channels` per texel (1: grey, 2: grey and
// alpha, 3: RGB, 4: RGBA). 8-bit sources keep their bytes, decoded when read: a quarter of the
// memory of floats, and four times the texels per cache line, which is what a texture lookup
// waits on. Half-float sources (most EXR environment maps) and linear 16-bit ones (normal maps)
// keep their halves or codes: half the memory of floats, exactly the same values. Radiance .hdr
// sources keep their shared-exponent texels: a third of the memory of floats, exactly the same
// values. Everything else (float, sRGB 16-bit) is held as linear floats.
struct ImageDesc {
  std::string name;
  int width = 0, height = 0, channels = 0;
  std::vector<float> texels;     // linear, when the image is held as floats
  std::vector<uint8_t> bytes;    // the 8-bit codes as stored in the file, when held as bytes
  std::vector<uint16_t> halves;  // linear half floats as stored in the file, when held as halves
  std::vector<uint16_t> words;   // linear 16-bit codes as stored in the file, when held as words
  std::vector<RgbeTexel> rgbe;   // one per texel (channels is 3), when held as RGBE
  bool srgb = false;             // the bytes' colour channels are sRGB-encoded (alpha never is)
  // The image's MIP levels after this one, each half the size of the one before down to 1x1, held
  // as bytes or 16-bit codes when the image is, else as floats (core/mip_levels.h); empty unless
  // textures are filtered by their footprint.
  std::vector<ImageDesc> mips;

  bool holds_bytes() const { return !bytes.empty(); }
  bool holds_halves() const { return !halves.empty(); }
  bool holds_words() const { return !words.empty(); }
  bool holds_rgbe() const { return !rgbe.empty(); }
  size_t texel_count() const { return size_t(width) * size_t(height); }
  size_t memory_bytes() const {
    size_t sum = texels.size() * sizeof(float) + bytes.size() + (halves.size() + words.size()) * sizeof(uint16_t) +
                 rgbe.size() * sizeof(RgbeTexel);
    for (const ImageDesc& level : mips) sum += level.memory_bytes();
    return sum;
  }
  // MIP level k: 0 is this image, 1 the first of `mips`; clamped to the coarsest.
  const ImageDesc& level(int k) const {
    return k <= 0 || mips.empty() ? *this : mips[size_t(std::min(k, int(mips.size()))) - 1];
  }

  // Starts fetching the texel at column x, row y into the cache.
  void prefetch(int x, int y) const {
    const size_t texel = size_t(y) * size_t(width) + size_t(x), i = texel * size_t(channels);
    if (!bytes.empty())
      __builtin_prefetch(&bytes[i]);
    else if (!rgbe.empty())
      __builtin_prefetch(&rgbe[texel]);
    else if (!halves.empty())
      __builtin_prefetch(&halves[i]);
    else if (!words.empty())
      __builtin_prefetch(&words[i]);
    else
      __builtin_prefetch(&texels[i]);
  }

 private:
  // f(read) for stored values v, `channels` per texel: the colour channels through `colour`, alpha
  // through `alpha`.
  template <typename Stored, typename Colour, typename Alpha, typename F>
  decltype(auto) with_channels(const Stored* v, Colour colour, Alpha alpha, F& f) const {
    const size_t w = size_t(width);
    const auto at = [v, w](int x, int y, size_t n) { return v + (size_t(y) * w + size_t(x)) * n; };
    switch (channels) {
      case 1:
        return f([=](int x, int y) { return Rgba{Rgb(colour(*at(x, y, 1))), 1.0f}; });
      case 2:
        return f([=](int x, int y) {
          const Stored* p = at(x, y, 2);
          return Rgba{Rgb(colour(p[0])), alpha(p[1])};
        });
      case 3:
        return f([=](int x, int y) {
          const Stored* p = at(x, y, 3);
          return Rgba{Rgb(colour(p[0]), colour(p[1]), colour(p[2])), 1.0f};
        });
      default:
        return f([=](int x, int y) {
          const Stored* p = at(x, y, 4);
          return Rgba{Rgb(colour(p[0]), colour(p[1]), colour(p[2])), alpha(p[3])};
        });
    }
  }

 public:
  // f(read), where read(x, y) is texel(x, y) for this image's storage and channel count, chosen
  // once: a lookup that reads several texels (a bilinear one reads four) decides how once, and
  // each read is inlined.
  template <typename F>
  decltype(auto) with_reader(F&& f) const {
    if (!bytes.empty()) {
      const std::array<float, 256>& colour = srgb ? kSrgbCodes : kLinearCodes;
      return with_channels(bytes.data(), [&colour](uint8_t c) { return colour[c]; },
                           [](uint8_t c) { return kLinearCodes[c]; }, f);
    }
    if (!rgbe.empty()) {
      const RgbeTexel* const t = rgbe.data();
      const int w = width;
      return f([t, w](int x, int y) { return Rgba{rgbe_to_rgb(t[size_t(y) * size_t(w) + size_t(x)]), 1.0f}; });
    }
    if (!halves.empty()) return with_channels(halves.data(), half_to_float, half_to_float, f);
    if (!words.empty()) {
      // code x (1 / 65535), as OpenImageIO converts 16-bit samples to float.
      const auto unorm = [](uint16_t w) { return float(w) * (1.0f / 65535.0f); };
      return with_channels(words.data(), unorm, unorm, f);
    }
    const auto same = [](float v) { return v; };
    return with_channels(texels.data(), same, same, f);
  }

  // The texel at column x, row y, linear; grey is replicated to RGB, alpha is 1 without a channel.
  Rgba texel(int x, int y) const {
    return with_reader([x, y](const auto& read) { return read(x, y); });
  }
};

}  // namespace prism
