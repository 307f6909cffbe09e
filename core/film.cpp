#include "core/film.h"

#include "core/memory_limit.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <tuple>

namespace prism {

Film::Film(int width, int height, AovSet aovs) : width_(width), height_(height), aovs_(aovs) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("film size must be positive, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  const size_t n = size_t(width) * size_t(height);
  for (Aov a : kAveraged) average_stride_ += aovs.has(a) ? 3 : 0;
  // Accumulators, nearest-hit ids, a few Cryptomatte ids, and the float image written out.
  const uint64_t per_pixel = sizeof(Pixel) + 8 * uint64_t(average_stride_) + 16 +
                             (aovs.has(Aov::CryptoObject) || aovs.has(Aov::CryptoMaterial) ? 64 : 0) +
                             4 * (4 + uint64_t(average_stride_));
  require_memory(uint64_t(n) * per_pixel,
                 "a " + std::to_string(width) + "x" + std::to_string(height) + " film" +
                     (average_stride_ ? " with " + std::to_string(average_stride_) + " AOV channels" : ""));
  pixels_.resize(n);
  average_sums_.assign(n * size_t(average_stride_), 0.0);
  if (aovs.has(Aov::Depth) || aovs.has(Aov::ObjectId) || aovs.has(Aov::MaterialId)) {
    nearest_depth_.assign(n, kBackgroundDepth);
    nearest_object_.assign(n, -1);
    nearest_material_.assign(n, -1);
  }
  if (aovs.has(Aov::CryptoObject)) crypto_objects_.resize(n);
  if (aovs.has(Aov::CryptoMaterial)) crypto_materials_.resize(n);
}

int Film::average_slot(Aov aov) const {
  int slot = 0;
  for (Aov a : kAveraged) {
    if (!aovs_.has(a)) continue;
    if (a == aov) return slot;
    slot += 3;
  }
  return -1;
}

void Film::add_aov_sample(int x, int y, const AovSample& s, float depth) {
  if (average_stride_ > 0) {
    double* sums = average_sums(x, y);
    for (Aov a : kAveraged) {
      if (!aovs_.has(a)) continue;
      Vec3 v;
      switch (a) {
        case Aov::Albedo: v = s.albedo; break;
        case Aov::Normal: v = s.normal; break;
        case Aov::Position: v = s.position; break;
        case Aov::Emission: v = s.emission; break;
        case Aov::Direct: v = s.direct; break;
        default: v = s.indirect; break;
      }
      sums[0] += v.x;
      sums[1] += v.y;
      sums[2] += v.z;
      sums += 3;
    }
  }
  const size_t i = size_t(y) * width_ + x;
  if (tracks_nearest() && s.hit) keep_nearer(i, depth, s.object, s.material);
  if (s.hit && !crypto_objects_.empty() && size_t(s.object) < object_ids_.size())
    add_id_sample(crypto_objects_[i], object_ids_[size_t(s.object)]);
  if (s.hit && !crypto_materials_.empty() && size_t(s.material) < material_ids_.size())
    add_id_sample(crypto_materials_[i], material_ids_[size_t(s.material)]);
}

void Film::mean(int x, int y, float rgba[4]) const {
  const Pixel& px = pixel(x, y);
  const double inv = px.count ? 1.0 / double(px.count) : 0.0;
  for (int c = 0; c < 4; ++c) rgba[c] = static_cast<float>(px.sum[c] * inv);
}

void Film::track_halves() {
  if (!halves_.empty()) return;
  require_memory(uint64_t(pixels_.size()) * sizeof(Halves),
                 "the " + std::to_string(width_) + "x" + std::to_string(height_) + " film's half sums");
  halves_.resize(pixels_.size());
}

void Film::record_halves(int x, int y) {
  const Pixel& px = pixel(x, y);
  Halves& h = halves_[size_t(y) * width_ + x];
  h.lower = h.upper;
  h.lower_count = h.upper_count;
  h.upper = 0.2126 * px.sum[0] + 0.7152 * px.sum[1] + 0.0722 * px.sum[2];  // luminance(), in double
  h.upper_count = px.count;
}

Rgb Film::variance_of_mean(int x, int y) const {
  const Pixel& px = pixel(x, y);
  if (px.count < 2) return Rgb(0.0f);
  const double n = double(px.count);
  float v[3];
  for (int c = 0; c < 3; ++c) {
    // Sum-of-squares form in double: relative cancellation error ~1e-16 * n, far below the noise.
    const double sample_variance = std::max(0.0, (px.sum_sq[c] - px.sum[c] * px.sum[c] / n) / (n - 1));
    v[c] = static_cast<float>(sample_variance / n);
  }
  return {v[0], v[1], v[2]};
}

std::vector<float> Film::resolve_rgba() const {
  std::vector<float> out(size_t(width_) * height_ * 4);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) mean(x, y, &out[(size_t(y) * width_ + x) * 4]);
  return out;
}

Film::SampleCounts Film::sample_counts() const {
  SampleCounts c{~uint64_t(0), 0, 0};
  for (const Pixel& p : pixels_) {
    c.min = std::min(c.min, p.count);
    c.max = std::max(c.max, p.count);
    c.total += p.count;
  }
  return c;
}

std::vector<float> Film::resolve_counts() const {
  std::vector<float> out(pixels_.size());
  for (size_t i = 0; i < pixels_.size(); ++i) out[i] = static_cast<float>(pixels_[i].count);
  return out;
}

std::vector<float> Film::resolve_average(Aov aov, int c) const {
  const int slot = average_slot(aov);
  if (slot < 0) throw std::invalid_argument("the film does not accumulate AOV " + aov_name(aov));
  std::vector<float> out(pixels_.size());
  for (size_t i = 0; i < pixels_.size(); ++i) {
    const uint64_t n = pixels_[i].count;
    out[i] = n ? static_cast<float>(average_sums_[i * size_t(average_stride_) + size_t(slot + c)] / double(n)) : 0.0f;
  }
  return out;
}

void Film::keep_nearer(size_t i, float depth, int32_t object, int32_t material) {
  // The nearest hit is the smallest (depth, object, material): at equal depth the smaller ids, so
  // the result does not depend on how the samples were split into parts and merged.
  if (std::tuple(depth, object, material) < std::tuple(nearest_depth_[i], nearest_object_[i], nearest_material_[i])) {
    nearest_depth_[i] = depth;
    nearest_object_[i] = object;
    nearest_material_[i] = material;
  }
}

void Film::merge(const Film& other, int x0, int y0) {
  if (!(other.aovs_ == aovs_) || x0 < 0 || y0 < 0 || x0 + other.width_ > width_ || y0 + other.height_ > height_)
    throw std::invalid_argument("a film merges only into a film with its AOVs that contains its window");
  for (int y = 0; y < other.height_; ++y)
    for (int x = 0; x < other.width_; ++x) {
      const size_t j = size_t(y) * other.width_ + x, i = size_t(y + y0) * width_ + size_t(x + x0);
      Pixel& a = pixels_[i];
      const Pixel& b = other.pixels_[j];
      for (int c = 0; c < 4; ++c) a.sum[c] += b.sum[c];
      for (int c = 0; c < 3; ++c) a.sum_sq[c] += b.sum_sq[c];
      a.count += b.count;
      if (tracks_halves()) halves_[i] = Halves{};  // the sums no longer follow sample indices
      for (int k = 0; k < average_stride_; ++k)
        average_sums_[i * size_t(average_stride_) + size_t(k)] += other.average_sums_[j * size_t(average_stride_) + size_t(k)];
      if (tracks_nearest()) keep_nearer(i, other.nearest_depth_[j], other.nearest_object_[j], other.nearest_material_[j]);
      for (auto [mine, theirs] : {std::pair(&crypto_objects_, &other.crypto_objects_),
                                  std::pair(&crypto_materials_, &other.crypto_materials_)}) {
        if (mine->empty()) continue;
        for (const IdCount& c : (*theirs)[j]) add_id_count((*mine)[i], c.id, c.count);
      }
    }
}

}  // namespace prism
