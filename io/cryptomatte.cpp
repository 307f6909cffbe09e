#include "io/cryptomatte.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace prism {
namespace {

constexpr const char* kRgba[4] = {"R", "G", "B", "A"};

// The 8 lower-case hex digits of v, most significant first (the manifest's "%08x", spec 1.e).
std::string hex8(uint32_t v) {
  constexpr char kDigits[] = "0123456789abcdef";
  std::string s(8, '0');
  for (int i = 7; i >= 0; --i, v >>= 4) s[static_cast<size_t>(i)] = kDigits[v & 0xfu];
  return s;
}

// "<layer>NN.<c>": rank layers are numbered with (at least) two digits, spec 1.b.
std::string rank_channel_name(const std::string& layer, int index, const char* component) {
  std::string nn = std::to_string(index);
  if (nn.size() < 2) nn.insert(0, 2 - nn.size(), '0');
  return layer + nn + "." + component;
}

}  // namespace

uint32_t murmur_hash3_32(std::string_view key, uint32_t seed) {
  constexpr uint32_t c1 = 0xcc9e2d51u, c2 = 0x1b873593u;
  const auto byte = [&](size_t i) { return static_cast<uint32_t>(static_cast<unsigned char>(key[i])); };
  const auto mix_k = [&](uint32_t k) { return std::rotl(k * c1, 15) * c2; };

  const size_t n = key.size();
  uint32_t h = seed;
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {  // 4-byte blocks read little-endian whatever the host's byte order
    const uint32_t k = byte(i) | byte(i + 1) << 8 | byte(i + 2) << 16 | byte(i + 3) << 24;
    h ^= mix_k(k);
    h = std::rotl(h, 13) * 5 + 0xe6546b64u;
  }
  uint32_t tail = 0;  // the last 1-3 bytes, also little-endian, mixed without the rotate-multiply-add
  for (size_t j = n; j > i; --j) tail = tail << 8 | byte(j - 1);
  if (n > i) h ^= mix_k(tail);

  h ^= static_cast<uint32_t>(n);  // the reference takes the length as a 32-bit int
  h ^= h >> 16;                   // fmix32
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

uint32_t cryptomatte_id_bits(std::string_view name) {
  // Spec 2, "Floating point conversion" (uint32_to_float32): a bit-for-bit copy of the hash, except
  // that an exponent of 0 (zero/denormal) or 255 (Inf/NaN) gets its lowest bit flipped, i.e. becomes
  // 1 or 254, as Psyop's reference code does; the same as the spec text's clamp to [1, 254].
  uint32_t h = murmur_hash3_32(name, 0);
  const uint32_t exponent = (h >> 23) & 0xffu;
  if (exponent == 0 || exponent == 0xffu) h ^= 1u << 23;
  return h;
}

float cryptomatte_id(std::string_view name) { return std::bit_cast<float>(cryptomatte_id_bits(name)); }

std::string cryptomatte_layer_key(std::string_view layer) {
  // Spec 1.d only asks for a stable key of at most 7 characters and suggests a hash of the type
  // name; Psyop's tools drop the last hex digit of the name's id.
  return hex8(cryptomatte_id_bits(layer)).substr(0, 7);
}


std::vector<ExrChannel> cryptomatte_channels(const std::string& layer, const std::vector<PixelIdCounts>& pixels,
                                             const std::vector<uint64_t>& samples_per_pixel, int ranks) {
  if (ranks < 1) throw std::invalid_argument("cryptomatte: ranks must be at least 1");
  if (pixels.size() != samples_per_pixel.size())
    throw std::invalid_argument("cryptomatte: id counts and sample counts cover different pixel counts");

  const size_t n = pixels.size();
  const int layers = (ranks + 1) / 2;
  std::vector<ExrChannel> channels(static_cast<size_t>(layers) * 4);
  for (int l = 0; l < layers; ++l)
    for (int c = 0; c < 4; ++c) {
      ExrChannel& ch = channels[static_cast<size_t>(l * 4 + c)];
      ch.name = rank_channel_name(layer, l, kRgba[c]);
      ch.type = ExrPixelType::Float;
      ch.values.assign(n, 0.0f);
    }

  // Spec 3.a: rank by coverage, highest first; all of a pixel's coverages share the denominator, so
  // ranking by count is the same. Ties go to the lower id so the output does not depend on the order
  // the ids were met in.
  const auto higher_rank = [](const IdCount& a, const IdCount& b) {
    return a.count != b.count ? a.count > b.count : a.id < b.id;
  };
  PixelIdCounts ranked;
  for (size_t p = 0; p < n; ++p) {
    const uint64_t samples = samples_per_pixel[p];
    if (samples == 0) continue;
    ranked = pixels[p];
    const size_t kept = std::min(ranked.size(), static_cast<size_t>(ranks));
    const auto last = ranked.begin() + static_cast<std::ptrdiff_t>(kept);
    std::partial_sort(ranked.begin(), last, ranked.end(), higher_rank);
    for (size_t r = 0; r < kept; ++r) {
      if (ranked[r].count == 0) break;  // an id never sampled has no coverage: leave the rank unused
      const size_t base = (r / 2) * 4 + (r % 2) * 2;  // R,G for even ranks, B,A for odd ones
      channels[base].values[p] = std::bit_cast<float>(ranked[r].id);
      const double coverage = static_cast<double>(ranked[r].count) / static_cast<double>(samples);
      channels[base + 1].values[p] = static_cast<float>(coverage);
    }
  }
  return channels;
}

std::vector<ExrAttribute> cryptomatte_attributes(const std::string& layer, const std::vector<std::string>& names) {
  // Spec 1.e: the manifest maps each name to the hex digits of its float id's bits. nlohmann's object
  // is a std::map, so the keys come out once each and sorted (byte-wise), whatever the input order.
  nlohmann::json manifest = nlohmann::json::object();
  for (const std::string& name : names) manifest[name] = hex8(cryptomatte_id_bits(name));

  const std::string prefix = "cryptomatte/" + cryptomatte_layer_key(layer) + "/";
  // Invalid UTF-8 in a name is written as U+FFFD rather than failing the whole render.
  std::string json = manifest.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return {
      {prefix + "name", layer},
      {prefix + "hash", std::string("MurmurHash3_32")},
      {prefix + "conversion", std::string("uint32_to_float32")},
      {prefix + "manifest", std::move(json)},
  };
}

std::vector<PixelIdCounts> cryptomatte_counts(const ExrImage& image, const std::string& layer,
                                              const std::vector<uint64_t>& samples_per_pixel) {
  const size_t n = image.data.empty()
                       ? 0
                       : static_cast<size_t>(image.data.width()) * static_cast<size_t>(image.data.height());
  if (samples_per_pixel.size() != n)
    throw std::invalid_argument("cryptomatte: sample counts do not cover the data window");

  std::vector<PixelIdCounts> pixels(n);
  for (int l = 0; image.find(rank_channel_name(layer, l, "R")); ++l) {
    const ExrChannel* ch[4];
    for (int c = 0; c < 4; ++c) {
      const std::string name = rank_channel_name(layer, l, kRgba[c]);
      ch[c] = image.find(name);
      if (!ch[c]) throw std::runtime_error("cryptomatte: rank layer lacks channel " + name);
      if (ch[c]->values.size() != n)
        throw std::runtime_error("cryptomatte: channel " + name + " does not cover the data window");
    }
    for (size_t p = 0; p < n; ++p) {
      if (samples_per_pixel[p] == 0) continue;
      for (int pair = 0; pair < 2; ++pair) {
        const float coverage = ch[pair * 2 + 1]->values[p];
        if (!(coverage > 0.0f)) continue;  // an unused rank (the test also rejects NaN)
        // In double: float coverage times more than 2^24 samples would lose whole counts.
        const double count = static_cast<double>(coverage) * static_cast<double>(samples_per_pixel[p]);
        if (count < 0.5) continue;  // rounds to no sample at all
        const uint32_t id = std::bit_cast<uint32_t>(ch[pair * 2]->values[p]);
        add_id_count(pixels[p], id,
                     count >= UINT32_MAX ? UINT32_MAX : static_cast<uint32_t>(std::llround(count)));
      }
    }
  }
  return pixels;
}

}  // namespace prism
