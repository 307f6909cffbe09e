#include "materials/texture_lookup.h"

#include <cmath>

namespace prism {

int wrap_texel(int i, int n, WrapMode mode) {
  switch (mode) {
    case WrapMode::ClampToEdge:
      return i < 0 ? 0 : (i >= n ? n - 1 : i);
    case WrapMode::MirroredRepeat: {
      const int period = 2 * n;
      int m = i % period;
      if (m < 0) m += period;
      return m < n ? m : period - 1 - m;
    }
    case WrapMode::Repeat:
    default: {
      const int m = i % n;
      return m < 0 ? m + n : m;
    }
  }
}

namespace {

// Integer part of a float coordinate, clamped to stay inside int for any uv.
int floor_to_int(float v) {
  const float f = std::floor(v);
  return f < -1e9f ? -1000000000 : (f > 1e9f ? 1000000000 : static_cast<int>(f));
}

}  // namespace

Rgba lookup_texture(const SceneDesc& scene, const TextureRef& ref, Vec2 uv) {
  uv = ref.apply(uv);
  const TextureDesc& tex = scene.textures[ref.texture];
  const ImageDesc& img = scene.images[tex.image];
  if (img.width <= 0 || img.height <= 0 || !std::isfinite(uv.x) || !std::isfinite(uv.y)) return {};
  const float x = uv.x * static_cast<float>(img.width) - 0.5f;  // texel centres at half-integers
  const float y = uv.y * static_cast<float>(img.height) - 0.5f;
  if (tex.nearest) {
    return img.texel(wrap_texel(floor_to_int(x + 0.5f), img.width, tex.wrap_s),
                     wrap_texel(floor_to_int(y + 0.5f), img.height, tex.wrap_t));
  }
  const int x0 = floor_to_int(x), y0 = floor_to_int(y);
  const float fx = x - std::floor(x), fy = y - std::floor(y);
  const int xa = wrap_texel(x0, img.width, tex.wrap_s), xb = wrap_texel(x0 + 1, img.width, tex.wrap_s);
  const int ya = wrap_texel(y0, img.height, tex.wrap_t), yb = wrap_texel(y0 + 1, img.height, tex.wrap_t);
  const Rgba a = img.texel(xa, ya), b = img.texel(xb, ya), c = img.texel(xa, yb), d = img.texel(xb, yb);
  const float wa = (1 - fx) * (1 - fy), wb = fx * (1 - fy), wc = (1 - fx) * fy, wd = fx * fy;
  return {a.rgb * wa + b.rgb * wb + c.rgb * wc + d.rgb * wd, a.a * wa + b.a * wb + c.a * wc + d.a * wd};
}

}  // namespace prism
