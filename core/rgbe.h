// Rgbe: Radiance's shared-exponent texels (.hdr files), decoded exactly as OpenImageIO decodes them.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>

#include "core/vec3.h"

namespace prism {

// A texel of Radiance's RGBE format (G. Ward, "Real Pixels", Graphics Gems II, 1991): three 8-bit
// mantissas in bytes 0-2 (red, green, blue) and one exponent in byte 3. Channel c is
// mantissa_c x 2^(exponent - 136); exponent 0 is black. A quarter of the memory of three floats.
using RgbeTexel = uint32_t;

// 2^(e - 136) for e = 1..255, 0 for e = 0: halving from 2^119 is exact down to 2^-135 (a denormal).
inline constexpr std::array<float, 256> kRgbeScales = [] {
  std::array<float, 256> s{};
  float scale = 0x1p119f;  // 2^(255 - 136)
  for (int e = 255; e >= 1; --e, scale *= 0.5f) s[size_t(e)] = scale;
  return s;
}();

// The colour an RGBE texel holds: each mantissa times the exponent's scale in float, as OpenImageIO
// reads .hdr files (its rgbe2float, without Radiance's half-step bias).
inline Rgb rgbe_to_rgb(RgbeTexel t) {
  const float scale = kRgbeScales[t >> 24];
  return {float(t & 0xffu) * scale, float((t >> 8) & 0xffu) * scale, float((t >> 16) & 0xffu) * scale};
}

// The texel that rgbe_to_rgb turns back into exactly c (bit for bit), if there is one. The exponent
// puts the largest channel's mantissa in [128, 256) (or is 1, for the tiniest colours); any texel
// that decodes to c has its mantissas at most that far shifted, so a colour read from an .hdr file
// always has one. Called for every
// texel of a map as it loads: no libm calls.
inline std::optional<RgbeTexel> exact_rgbe(const Rgb& c) {
  const float largest = std::max({c.x, c.y, c.z});
  RgbeTexel t = 0;
  if (largest > 0 && std::isfinite(largest)) {  // black stays 0; NaN and negative colours fail below
    // largest = f 2^exponent with f in [0.5, 1), from the float's exponent field (frexp for denormals).
    const uint32_t field = std::bit_cast<uint32_t>(largest) >> 23;
    int exponent = int(field) - 126;
    if (field == 0) (void)std::frexp(largest, &exponent);
    // Below 2^-127 the mantissas cannot reach 128: exponent 1 leaves them smaller.
    const int e = std::max(exponent + 128, 1);
    if (e > 255) return std::nullopt;
    t = RgbeTexel(e) << 24;
    const double unscale = 1.0 / double(kRgbeScales[size_t(e)]);  // a power of two: exact
    for (int k = 0; k < 3; ++k) {
      const double mantissa = double(c[k]) * unscale;  // exact: a float times a power of two, in a double
      if (!(mantissa >= 0 && mantissa <= 255)) return std::nullopt;
      const uint32_t code = uint32_t(mantissa);
      if (double(code) != mantissa) return std::nullopt;
      t |= code << (8 * k);
    }
  }
  const Rgb back = rgbe_to_rgb(t);
  for (int k = 0; k < 3; ++k)
    if (std::bit_cast<uint32_t>(back[k]) != std::bit_cast<uint32_t>(c[k])) return std::nullopt;
  return t;
}

}  // namespace prism
