#include "core/mip_levels.h"

#include <algorithm>
#include <cmath>

#include "core/memory_limit.h"
#include "core/parallel_ranges.h"

namespace prism {

uint8_t nearest_code(const std::array<float, 256>& codes, float v) {
  const auto above = std::lower_bound(codes.begin(), codes.end(), v);
  if (above == codes.begin()) return 0;
  if (above == codes.end()) return 255;
  const auto below = above - 1;
  return uint8_t((v - *below <= *above - v ? below : above) - codes.begin());
}

namespace {

// nearest_code without a search: the nearest code of v is at or after the nearest code of
// floor(v x 4096) / 4096 (codes rise).
class CodeEncoder {
 public:
  explicit CodeEncoder(const std::array<float, 256>& codes) : codes_(codes) {
    for (int b = 0; b <= kBuckets; ++b) start_[size_t(b)] = nearest_code(codes, float(b) / kBuckets);
  }
  uint8_t operator()(float v) const {
    if (!(v > 0)) return 0;
    if (v >= 1) return 255;
    // Codes lie at least a bucket apart (sRGB's closest, near 0, are 1 / 3295 apart; a bucket is
    // 1 / 4096), so the nearest is the bucket's start or the code after it.
    const int c = start_[size_t(v * kBuckets)];
    const int next = std::min(c + 1, 255);
    return uint8_t(std::abs(codes_[size_t(next)] - v) < std::abs(codes_[size_t(c)] - v) ? next : c);
  }

 private:
  static constexpr int kBuckets = 4096;
  const std::array<float, 256>& codes_;
  std::array<uint8_t, kBuckets + 1> start_{};
};

// Source texels [first(i), first(i + 1)) of n map to texel i of m = max(1, n / 2): two each, and
// three for the last when n is odd.
int first_source(int i, int n, int m) { return n == 2 * m ? 2 * i : int(int64_t(i) * n / m); }

// The level below `src` (src's kind: codes for codes, floats otherwise), each texel the mean of
// the block of src's texels it covers, read by `read(x, y, out)` (C linear values) and stored by
// `store(texel index, values)`.
template <int C, typename Read, typename Store>
void halve(int width, int height, int out_width, int out_height, const Read& read, const Store& store) {
  parallel_ranges(out_height, 0, [&](int first, int end) {
    for (int y = first; y != end; ++y) {
      const int y0 = first_source(y, height, out_height), y1 = first_source(y + 1, height, out_height);
      for (int x = 0; x < out_width; ++x) {
        const int x0 = first_source(x, width, out_width), x1 = first_source(x + 1, width, out_width);
        float sum[C] = {}, texel[C];
        for (int sy = y0; sy < y1; ++sy)
          for (int sx = x0; sx < x1; ++sx) {
            read(sx, sy, texel);
            for (int k = 0; k < C; ++k) sum[k] += texel[k];
          }
        const float count = float((y1 - y0) * (x1 - x0));  // 4, 6 or 9: exact in float
        for (int k = 0; k < C; ++k) sum[k] /= count;
        store(size_t(y) * size_t(out_width) + size_t(x), sum);
      }
    }
  });
}

// The levels of an image of C channels, each from the one before.
template <int C>
void build_levels(ImageDesc& image) {
  constexpr bool kAlpha = C == 2 || C == 4;  // the last channel is alpha, always linear
  const CodeEncoder linear(kLinearCodes), colour(image.srgb ? kSrgbCodes : kLinearCodes);
  const std::array<float, 256>& colours = image.srgb ? kSrgbCodes : kLinearCodes;
  const ImageDesc* src = &image;
  while (src->width > 1 || src->height > 1) {
    ImageDesc level;
    level.name = image.name;
    level.width = std::max(1, src->width / 2);
    level.height = std::max(1, src->height / 2);
    level.channels = C;
    level.srgb = image.srgb;
    const size_t n = level.texel_count() * C;
    const auto halve_into = [&](const auto& read, const auto& store) {
      halve<C>(src->width, src->height, level.width, level.height, read, store);
    };
    const size_t src_width = size_t(src->width);
    if (image.holds_bytes()) {
      // Codes through their tables, and the nearest code to each mean.
      level.bytes.resize(n);
      halve_into(
          [&](int x, int y, float* out) {
            const uint8_t* b = &src->bytes[(size_t(y) * src_width + size_t(x)) * C];
            for (int k = 0; k < C; ++k) out[k] = (kAlpha && k == C - 1 ? kLinearCodes : colours)[b[k]];
          },
          [&](size_t t, const float* v) {
            for (int k = 0; k < C; ++k) level.bytes[t * C + size_t(k)] = (kAlpha && k == C - 1 ? linear : colour)(v[k]);
          });
    } else if (image.holds_words()) {
      level.words.resize(n);
      halve_into(
          [&](int x, int y, float* out) {
            const uint16_t* w = &src->words[(size_t(y) * src_width + size_t(x)) * C];
            for (int k = 0; k < C; ++k) out[k] = float(w[k]) * (1.0f / 65535.0f);
          },
          [&](size_t t, const float* v) {
            for (int k = 0; k < C; ++k)
              level.words[t * C + size_t(k)] = uint16_t(std::lround(std::clamp(v[k], 0.0f, 1.0f) * 65535.0f));
          });
    } else {
      level.texels.resize(n);
      halve_into(
          [&](int x, int y, float* out) {
            const Rgba t = src->texel(x, y);
            const float all[4] = {t.rgb.x, t.rgb.y, t.rgb.z, t.a};
            for (int k = 0; k < C; ++k) out[k] = C == 2 && k == 1 ? all[3] : all[k];
          },
          [&](size_t t, const float* v) {
            for (int k = 0; k < C; ++k) level.texels[t * C + size_t(k)] = v[k];
          });
    }
    image.mips.push_back(std::move(level));
    src = &image.mips.back();
  }
}

}  // namespace

void build_texture_mips(SceneDesc& scene, const std::string& source) {
  std::vector<bool> filtered(scene.images.size(), false);
  for (const MaterialDesc& m : scene.materials)
    for (const TextureRef* ref : m.texture_slots()) {
      if (!ref->present() || ref == &m.emissive_texture || ref->texture >= int(scene.textures.size())) continue;
      const TextureDesc& tex = scene.textures[size_t(ref->texture)];
      if (!tex.nearest && tex.image >= 0 && tex.image < int(scene.images.size())) filtered[size_t(tex.image)] = true;
    }
  // Levels add a third of a texel per texel, as codes when the image holds codes, else as floats.
  uint64_t total = 0;
  for (size_t i = 0; i < scene.images.size(); ++i) {
    const ImageDesc& image = scene.images[i];
    total += image.memory_bytes();
    if (!filtered[i]) continue;
    const uint64_t per_value = image.holds_bytes() ? 1 : image.holds_words() ? 2 : 4;
    total += image.texel_count() * uint64_t(std::max(image.channels, 0)) * per_value / 3 + 64;
  }
  require_memory(total, source + ": the textures with their MIP levels");
  for (size_t i = 0; i < scene.images.size(); ++i)
    if (filtered[i]) build_mip_levels(scene.images[i]);
}

void build_mip_levels(ImageDesc& image) {
  image.mips.clear();
  if (image.width <= 0 || image.height <= 0 || image.texel_count() == 1) return;
  switch (image.channels) {
    case 1: build_levels<1>(image); break;
    case 2: build_levels<2>(image); break;
    case 3: build_levels<3>(image); break;
    case 4: build_levels<4>(image); break;
    default: break;
  }
}

}  // namespace prism
