#include "io/render_layers.h"

#include <string>

#include "io/cryptomatte.h"
#include "io/exr_writer.h"

namespace prism {
namespace {

std::vector<std::string> object_names(const SceneDesc& scene) {
  std::vector<std::string> names;
  for (size_t i = 0; i < scene.object_count(); ++i) names.push_back(scene.object_name(i));
  return names;
}

std::vector<std::string> material_names(const SceneDesc& scene) {
  std::vector<std::string> names;
  for (size_t i = 0; i <= scene.materials.size(); ++i) names.push_back(scene.material_name(i));
  return names;
}

std::vector<uint32_t> ids_of(const std::vector<std::string>& names) {
  std::vector<uint32_t> ids;
  for (const std::string& n : names) ids.push_back(cryptomatte_id_bits(n));
  return ids;
}

}  // namespace

std::vector<uint32_t> object_cryptomatte_ids(const SceneDesc& scene) { return ids_of(object_names(scene)); }
std::vector<uint32_t> material_cryptomatte_ids(const SceneDesc& scene) { return ids_of(material_names(scene)); }

void add_render_layers(const Film& film, const SceneDesc* scene, const LayerOptions& options, ExrImage& image) {
  const int w = film.width(), h = film.height();
  const size_t n = size_t(w) * size_t(h);
  const AovSet& aovs = film.aovs();
  auto add = [&](std::string name, ExrPixelType type, std::vector<float> values) {
    image.channels.push_back({std::move(name), type, std::move(values), {}});
  };
  for (ExrChannel& c : rgba_channels(w, h, film.resolve_rgba(), options.beauty)) image.channels.push_back(std::move(c));
  for (const AveragedLayer& a : kAveragedLayers) {
    if (!aovs.has(a.aov)) continue;
    for (int c = 0; c < 3; ++c)
      add(std::string(a.layer) + "." + a.components[c], a.light ? options.beauty : ExrPixelType::Float,
          film.resolve_average(a.aov, c));
  }
  if (film.tracks_nearest()) {
    std::vector<float> depth(n), object(n), material(n);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        depth[i] = film.nearest_depth(x, y);
        object[i] = float(film.nearest_object(x, y));
        material[i] = float(film.nearest_material(x, y));
      }
    if (aovs.has(Aov::Depth)) add("Z", ExrPixelType::Float, std::move(depth));
    if (aovs.has(Aov::ObjectId)) add("object_id.V", ExrPixelType::Float, std::move(object));
    if (aovs.has(Aov::MaterialId)) add("material_id.V", ExrPixelType::Float, std::move(material));
  }
  if (aovs.has(Aov::Variance)) {
    std::vector<float> v[3] = {std::vector<float>(n), std::vector<float>(n), std::vector<float>(n)};
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const Rgb var = film.variance_of_mean(x, y);
        for (int c = 0; c < 3; ++c) v[c][size_t(y) * w + x] = var[c];
      }
    for (int c = 0; c < 3; ++c) add(std::string("variance.") + "RGB"[c], ExrPixelType::Float, std::move(v[c]));
  }
  std::vector<float> counts = film.resolve_counts();
  bool uniform = true;
  for (float c : counts) uniform = uniform && c == counts[0];
  if (aovs.has(Aov::Spp) || !uniform) add("spp.V", ExrPixelType::Float, counts);

  std::vector<uint64_t> samples(n);
  for (size_t i = 0; i < n; ++i) samples[i] = uint64_t(counts[i]);
  auto cryptomatte = [&](const char* layer, const std::vector<PixelIdCounts>& ids, auto names) {
    for (ExrChannel& c : cryptomatte_channels(layer, ids, samples, options.cryptomatte_ranks)) image.channels.push_back(std::move(c));
    if (scene)
      for (ExrAttribute& a : cryptomatte_attributes(layer, names(*scene))) image.attributes.push_back(std::move(a));
  };
  if (aovs.has(Aov::CryptoObject)) cryptomatte("CryptoObject", film.crypto_objects(), object_names);
  if (aovs.has(Aov::CryptoMaterial)) cryptomatte("CryptoMaterial", film.crypto_materials(), material_names);
}

}  // namespace prism
