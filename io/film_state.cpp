#include "io/film_state.h"

#include <bit>
#include <algorithm>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "io/cryptomatte.h"
#include "io/errors.h"
#include "io/render_layers.h"

namespace prism {
namespace {

constexpr const char* kPrefix = "prism.state.";

// The doubles of one pixel, in a fixed order: sum RGBA, squared sums RGB, count, AOV sums, and
// when the film tracks them its Halves (sums, then counts).
int doubles_per_pixel(const Film& film) { return 8 + film.average_slots() + (film.tracks_halves() ? 4 : 0); }

void pixel_doubles(const Film& film, int x, int y, double* out) {
  const Film::Pixel& p = film.pixel(x, y);
  for (int c = 0; c < 4; ++c) out[c] = p.sum[c];
  for (int c = 0; c < 3; ++c) out[4 + c] = p.sum_sq[c];
  out[7] = std::bit_cast<double>(p.count);
  for (int k = 0; k < film.average_slots(); ++k) out[8 + k] = film.average_sums(x, y)[k];
  if (film.tracks_halves()) {
    const Film::Halves& h = film.halves(x, y);
    double* o = out + 8 + film.average_slots();
    o[0] = h.lower;
    o[1] = h.upper;
    o[2] = std::bit_cast<double>(h.lower_count);
    o[3] = std::bit_cast<double>(h.upper_count);
  }
}

void set_pixel_doubles(Film& film, int x, int y, const double* in) {
  Film::Pixel& p = film.pixel(x, y);
  for (int c = 0; c < 4; ++c) p.sum[c] = in[c];
  for (int c = 0; c < 3; ++c) p.sum_sq[c] = in[4 + c];
  p.count = std::bit_cast<uint64_t>(in[7]);
  for (int k = 0; k < film.average_slots(); ++k) film.average_sums(x, y)[k] = in[8 + k];
  if (film.tracks_halves()) {
    const double* i = in + 8 + film.average_slots();
    film.halves(x, y) = {i[0], i[1], std::bit_cast<uint64_t>(i[2]), std::bit_cast<uint64_t>(i[3])};
  }
}

// Channel `name` when the image has it, checked to hold its pixels as `type` says: the film
// state in uint bits, the layers in float values (half widens to float on reading). A file
// whose channel has another type (a damaged or foreign file) is an InputError, not a read of
// the wrong array.
const ExrChannel* find(const ExrImage& image, const std::string& name, ExrPixelType type, const std::string& path) {
  const ExrChannel* c = image.find(name);
  if (!c) return nullptr;
  const size_t n = size_t(image.data.width()) * size_t(image.data.height());
  const bool bits = type == ExrPixelType::Uint;
  if ((c->type == ExrPixelType::Uint) != bits || (bits ? c->bits.size() : c->values.size()) != n)
    throw InputError(path, "channel " + name, bits ? "expected uint pixels (prism's film state)" : "expected half or float pixels");
  return c;
}

const ExrChannel& require(const ExrImage& image, const std::string& name, ExrPixelType type, const std::string& path) {
  const ExrChannel* c = find(image, name, type, path);
  if (!c) throw InputError(path, "channel " + name, "missing: the file was not written by a prism render with these layers");
  return *c;
}

AovSet aovs_of(const ExrImage& image, const std::string& path) {
  const ExrAttribute* a = image.attribute("prism/aovs");
  if (!a) return {};
  const std::string* list = std::get_if<std::string>(&a->second);
  try {
    return list ? parse_aovs(*list) : AovSet{};
  } catch (const std::invalid_argument& e) {
    throw InputError(path, "prism/aovs", e.what());
  }
}

// Cryptomatte counts, exactly: channels <prefix><name><k>.id and .count hold each pixel's k-th id
// and its sample count (count 0: no k-th id), for k below the most ids any pixel has.
void add_id_count_state(const std::vector<PixelIdCounts>& pixels, const std::string& name, ExrImage& image) {
  size_t most = 0;
  for (const PixelIdCounts& p : pixels) most = std::max(most, p.size());
  for (size_t k = 0; k < most; ++k) {
    std::vector<uint32_t> ids(pixels.size(), 0), counts(pixels.size(), 0);
    for (size_t i = 0; i < pixels.size(); ++i)
      if (k < pixels[i].size()) {
        ids[i] = pixels[i][k].id;
        counts[i] = pixels[i][k].count;
      }
    const std::string base = kPrefix + name + std::to_string(k);
    image.channels.push_back({base + ".id", ExrPixelType::Uint, {}, std::move(ids)});
    image.channels.push_back({base + ".count", ExrPixelType::Uint, {}, std::move(counts)});
  }
}

// The counts add_id_count_state wrote, or nullopt when the file has none (an image written
// without state, or a film without these ids).
std::optional<std::vector<PixelIdCounts>> id_count_state(const ExrImage& image, const std::string& name, size_t n,
                                                         const std::string& path) {
  if (!image.find(kPrefix + name + "0.id")) return std::nullopt;
  std::vector<PixelIdCounts> pixels(n);
  for (size_t k = 0;; ++k) {
    const std::string base = kPrefix + name + std::to_string(k);
    const ExrChannel* ids = find(image, base + ".id", ExrPixelType::Uint, path);
    const ExrChannel* counts = find(image, base + ".count", ExrPixelType::Uint, path);
    if (!ids || !counts) break;
    for (size_t i = 0; i < n; ++i)
      if (counts->bits[i] > 0) add_id_count(pixels[i], ids->bits[i], counts->bits[i]);
  }
  return pixels;
}

}  // namespace

void add_film_state(const Film& film, ExrImage& image) {
  const int w = film.width(), h = film.height(), k = doubles_per_pixel(film);
  const size_t n = size_t(w) * size_t(h);
  std::vector<std::vector<uint32_t>> words(size_t(2 * k), std::vector<uint32_t>(n));  // each double's high, low
  std::vector<double> d(static_cast<size_t>(k));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      pixel_doubles(film, x, y, d.data());
      for (int j = 0; j < k; ++j) {
        const uint64_t bits = std::bit_cast<uint64_t>(d[size_t(j)]);
        words[size_t(2 * j)][i] = uint32_t(bits >> 32);
        words[size_t(2 * j + 1)][i] = uint32_t(bits);
      }
    }
  for (int j = 0; j < k; ++j) {
    const std::string name = kPrefix + std::to_string(j);
    image.channels.push_back({name + "hi", ExrPixelType::Uint, {}, std::move(words[size_t(2 * j)])});
    image.channels.push_back({name + "lo", ExrPixelType::Uint, {}, std::move(words[size_t(2 * j + 1)])});
  }
  if (film.tracks_nearest()) {
    std::vector<uint32_t> depth(n), object(n), material(n);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        depth[i] = std::bit_cast<uint32_t>(film.nearest_depth(x, y));
        object[i] = std::bit_cast<uint32_t>(film.nearest_object(x, y));
        material[i] = std::bit_cast<uint32_t>(film.nearest_material(x, y));
      }
    image.channels.push_back({std::string(kPrefix) + "nearestDepth", ExrPixelType::Uint, {}, std::move(depth)});
    image.channels.push_back({std::string(kPrefix) + "nearestObject", ExrPixelType::Uint, {}, std::move(object)});
    image.channels.push_back({std::string(kPrefix) + "nearestMaterial", ExrPixelType::Uint, {}, std::move(material)});
  }
  if (film.aovs().has(Aov::CryptoObject)) add_id_count_state(film.crypto_objects(), "cryptoObject", image);
  if (film.aovs().has(Aov::CryptoMaterial)) add_id_count_state(film.crypto_materials(), "cryptoMaterial", image);
}

bool has_film_state(const ExrImage& image) { return image.find(std::string(kPrefix) + "0hi") != nullptr; }

Film film_from_image(const ExrImage& image, const std::string& path) {
  const int w = image.data.width(), h = image.data.height();
  Film film(w, h, aovs_of(image, path));
  const size_t n = size_t(w) * size_t(h);
  const bool exact = has_film_state(image);
  std::vector<uint64_t> counts(n);
  if (exact) {
    // Doubles past the film's own are its Halves (a render under a noise target with Sobol).
    if (image.find(kPrefix + std::to_string(doubles_per_pixel(film)) + "hi")) film.track_halves();
    const int k = doubles_per_pixel(film);
    std::vector<const ExrChannel*> channels;
    for (int j = 0; j < k; ++j)
      for (const char* half : {"hi", "lo"})
        channels.push_back(&require(image, kPrefix + std::to_string(j) + half, ExrPixelType::Uint, path));
    std::vector<double> d(static_cast<size_t>(k));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        for (int j = 0; j < k; ++j)
          d[size_t(j)] = std::bit_cast<double>(uint64_t(channels[size_t(2 * j)]->bits[i]) << 32 |
                                               channels[size_t(2 * j + 1)]->bits[i]);
        set_pixel_doubles(film, x, y, d.data());
        counts[i] = film.sample_count(x, y);
      }
    if (film.tracks_nearest()) {
      const ExrChannel& depth = require(image, std::string(kPrefix) + "nearestDepth", ExrPixelType::Uint, path);
      const ExrChannel& object = require(image, std::string(kPrefix) + "nearestObject", ExrPixelType::Uint, path);
      const ExrChannel& material = require(image, std::string(kPrefix) + "nearestMaterial", ExrPixelType::Uint, path);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const size_t i = size_t(y) * w + x;
          film.nearest_depth(x, y) = std::bit_cast<float>(depth.bits[i]);
          film.nearest_object(x, y) = std::bit_cast<int32_t>(object.bits[i]);
          film.nearest_material(x, y) = std::bit_cast<int32_t>(material.bits[i]);
        }
    }
  } else {
    // Counts: the spp layer, else the uniform count the header records.
    if (const ExrChannel* spp = find(image, "spp.V", ExrPixelType::Float, path)) {
      for (size_t i = 0; i < n; ++i) counts[i] = uint64_t(spp->values[i]);
    } else {
      const ExrAttribute* a = image.attribute("prism/sppMax");
      if (!a || !std::holds_alternative<int>(a->second))
        throw InputError(path, "prism/sppMax", "missing: no spp layer or sample count in the header");
      std::fill(counts.begin(), counts.end(), uint64_t(std::get<int>(a->second)));
    }
    const ExrChannel* rgba[4] = {&require(image, "R", ExrPixelType::Float, path), &require(image, "G", ExrPixelType::Float, path),
                                 &require(image, "B", ExrPixelType::Float, path), &require(image, "A", ExrPixelType::Float, path)};
    const ExrChannel* variance[3] = {find(image, "variance.R", ExrPixelType::Float, path),
                                     find(image, "variance.G", ExrPixelType::Float, path),
                                     find(image, "variance.B", ExrPixelType::Float, path)};
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        Film::Pixel& p = film.pixel(x, y);
        const double count = double(counts[i]);
        p.count = counts[i];
        for (int c = 0; c < 4; ++c) p.sum[c] = double(rgba[c]->values[i]) * count;
        // variance of the mean = (sum_sq - sum^2 / n) / ((n - 1) n), inverted; zero without a layer.
        for (int c = 0; c < 3; ++c) {
          const double v = variance[c] ? double(variance[c]->values[i]) : 0.0;
          p.sum_sq[c] = (count > 0 ? p.sum[c] * p.sum[c] / count : 0.0) + v * count * std::max(count - 1.0, 0.0);
        }
      }
    for (const AveragedLayer& l : kAveragedLayers) {
      const int slot = film.average_slot(l.aov);
      if (slot < 0) continue;
      for (int c = 0; c < 3; ++c) {
        const ExrChannel& ch = require(image, std::string(l.layer) + "." + l.components[c], ExrPixelType::Float, path);
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            film.average_sums(x, y)[slot + c] = double(ch.values[size_t(y) * w + x]) * double(counts[size_t(y) * w + x]);
      }
    }
    if (film.tracks_nearest()) {
      const ExrChannel* depth = find(image, "Z", ExrPixelType::Float, path);
      const ExrChannel* object = find(image, "object_id.V", ExrPixelType::Float, path);
      const ExrChannel* material = find(image, "material_id.V", ExrPixelType::Float, path);
      for (size_t i = 0; i < n; ++i) {
        const int x = int(i % size_t(w)), y = int(i / size_t(w));
        if (depth) film.nearest_depth(x, y) = depth->values[i];
        if (object) film.nearest_object(x, y) = int32_t(object->values[i]);
        if (material) film.nearest_material(x, y) = int32_t(material->values[i]);
      }
    }
  }
  try {
    // Exact counts from the state when there are any, else from the layers' top ranks.
    auto id_counts = [&](const std::string& state, const std::string& layer) {
      std::optional<std::vector<PixelIdCounts>> stored = id_count_state(image, state, n, path);
      return stored ? std::move(*stored) : cryptomatte_counts(image, layer, counts);
    };
    if (film.aovs().has(Aov::CryptoObject)) film.crypto_objects() = id_counts("cryptoObject", "CryptoObject");
    if (film.aovs().has(Aov::CryptoMaterial)) film.crypto_materials() = id_counts("cryptoMaterial", "CryptoMaterial");
  } catch (const std::exception& e) {
    throw InputError(path, "Cryptomatte layers", e.what());
  }
  return film;
}

}  // namespace prism
