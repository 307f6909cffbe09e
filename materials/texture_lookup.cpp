#include "materials/texture_lookup.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/hash.h"

namespace prism {

namespace {

// i modulo a positive period, in [0, period). Most textures are a power of two wide and high, where
// a mask gives it: an integer division, which it saves, takes tens of cycles, and a lookup has four.
int modulo(int i, int period) {
  if ((period & (period - 1)) == 0) return i & (period - 1);  // two's complement: floor modulo
  const int m = i % period;
  return m < 0 ? m + period : m;
}

}  // namespace

int wrap_texel(int i, int n, WrapMode mode) {
  switch (mode) {
    case WrapMode::ClampToEdge:
      return i < 0 ? 0 : (i >= n ? n - 1 : i);
    case WrapMode::MirroredRepeat: {
      const int period = 2 * n;
      const int m = modulo(i, period);
      return m < n ? m : period - 1 - m;
    }
    case WrapMode::Repeat:
    default:
      return modulo(i, n);
  }
}

namespace {

// A texel coordinate clamped to stay inside int for any finite uv (farther out, every float is an
// integer, so the wraps and weights are those of the clamped value's).
float clamp_coordinate(float v) { return std::min(std::max(v, -1e9f), 1e9f); }

// floor(v) for a clamped coordinate, without libm's floorf (a call on x86-64 without SSE4.1): the
// conversion truncates toward zero, one too high below zero unless v is an integer.
int floor_to_int(float v) {
  const int i = static_cast<int>(v);
  return i - int(static_cast<float>(i) > v);
}

// The texels a lookup at uv reads: the 2x2 block around it (bilinear, with the weights fx, fy of
// its right column and bottom row), or the nearest one alone (xa, ya).
struct Footprint {
  int xa = 0, xb = 0, ya = 0, yb = 0;
  float fx = 0, fy = 0;
};

std::optional<Footprint> footprint(const ImageDesc& img, const TextureDesc& tex, Vec2 uv) {
  if (img.width <= 0 || img.height <= 0 || !std::isfinite(uv.x) || !std::isfinite(uv.y)) return std::nullopt;
  // Texel centres at half-integers.
  const float x = clamp_coordinate(uv.x * static_cast<float>(img.width) - 0.5f);
  const float y = clamp_coordinate(uv.y * static_cast<float>(img.height) - 0.5f);
  Footprint f;
  if (tex.nearest) {
    f.xa = wrap_texel(floor_to_int(x + 0.5f), img.width, tex.wrap_s);
    f.ya = wrap_texel(floor_to_int(y + 0.5f), img.height, tex.wrap_t);
    return f;
  }
  const int x0 = floor_to_int(x), y0 = floor_to_int(y);
  f.fx = x - static_cast<float>(x0);  // x - floor(x), exactly: x0 is a float, and within 1 of x
  f.fy = y - static_cast<float>(y0);
  // The texel after a repeating one is the next, or the first after the last: no second modulo.
  const auto next = [](int a, int first, int n, WrapMode mode) {
    return mode == WrapMode::Repeat ? (a + 1 == n ? 0 : a + 1) : wrap_texel(first + 1, n, mode);
  };
  f.xa = wrap_texel(x0, img.width, tex.wrap_s);
  f.xb = next(f.xa, x0, img.width, tex.wrap_s);
  f.ya = wrap_texel(y0, img.height, tex.wrap_t);
  f.yb = next(f.ya, y0, img.height, tex.wrap_t);
  return f;
}

// The bilinear (or nearest) value of one image at uv.
Rgba filtered_texel(const ImageDesc& img, const TextureDesc& tex, Vec2 uv) {
  const std::optional<Footprint> f = footprint(img, tex, uv);
  if (!f) return {};
  if (tex.nearest) return img.texel(f->xa, f->ya);
  return img.with_reader([&f = *f](const auto& read) {
    const Rgba a = read(f.xa, f.ya), b = read(f.xb, f.ya), c = read(f.xa, f.yb), d = read(f.xb, f.yb);
    const float fx = f.fx, fy = f.fy;
    const float wa = (1 - fx) * (1 - fy), wb = fx * (1 - fy), wc = (1 - fx) * fy, wd = fx * fy;
    return Rgba{a.rgb * wa + b.rgb * wb + c.rgb * wc + d.rgb * wd, a.a * wa + b.a * wb + c.a * wc + d.a * wd};
  });
}

// The MIP level a footprint of uv_width (in the mesh's uv units) reads, as log2 of the level-0
// texels it spans (<= 0: level 0 alone). The texture transform scales the footprint by the square
// root of its area change; a non-square image's texels per uv unit are the geometric mean of its
// width and height.
float mip_lambda(const ImageDesc& img, const TextureDesc& tex, const TextureRef& ref, float uv_width) {
  if (!(uv_width > 0) || img.mips.empty() || tex.nearest) return 0;
  const std::array<float, 6>& t = ref.transform;
  const float area_scale = std::abs(t[0] * t[4] - t[1] * t[3]);
  const float texels = uv_width * std::sqrt(area_scale * float(img.width) * float(img.height));
  return texels > 1 && std::isfinite(texels) ? std::log2(texels) : 0.0f;
}

// Trilinear filtering picks level floor(lambda) + 1 with probability frac(lambda), else
// floor(lambda): the blend of the two levels in expectation, from the texels of one (Pharr et al.
// 2024, "Filtering after shading with stochastic texture filtering"). The choice is a hash of the
// lookup's coordinates, which the pixel's jitter makes a fresh uniform number for every sample.
int stochastic_level(float lambda, Vec2 at) {
  const int level = int(lambda);
  const float w = lambda - float(level);
  const float u = float(mix64((float_bits(at.x) << 32) | float_bits(at.y)) >> 40) * 0x1p-24f;
  return u < w ? level + 1 : level;
}

}  // namespace

Rgba lookup_texture(const SceneDesc& scene, const TextureRef& ref, Vec2 uv, float uv_width) {
  const TextureDesc& tex = scene.textures[ref.texture];
  const ImageDesc& img = scene.images[tex.image];
  const Vec2 at = ref.apply(uv);
  const float lambda = mip_lambda(img, tex, ref, uv_width);
  if (lambda <= 0) return filtered_texel(img, tex, at);
  return filtered_texel(img.level(stochastic_level(lambda, at)), tex, at);
}

void prefetch_texture(const SceneDesc& scene, const TextureRef& ref, Vec2 uv, float uv_width) {
  const TextureDesc& tex = scene.textures[ref.texture];
  const ImageDesc& base = scene.images[tex.image];
  const Vec2 at = ref.apply(uv);
  const float lambda = mip_lambda(base, tex, ref, uv_width);
  const ImageDesc& img = lambda > 0 ? base.level(stochastic_level(lambda, at)) : base;
  const std::optional<Footprint> f = footprint(img, tex, at);
  if (!f) return;
  img.prefetch(f->xa, f->ya);
  if (!tex.nearest) img.prefetch(f->xa, f->yb);  // the second row; xb is nearly always in xa's line
}

}  // namespace prism
