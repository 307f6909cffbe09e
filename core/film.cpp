#include "core/film.h"

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
  pixels_.resize(n);
  for (Aov a : kAveraged) average_stride_ += aovs.has(a) ? 3 : 0;
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
  // The nearest hit is the smallest (depth, object, material): at equal depth the smaller ids,
  // so a render split into parts and merged keeps the same one.
  if (tracks_nearest() && s.hit &&
      std::tuple(depth, s.object, s.material) <
          std::tuple(nearest_depth_[i], nearest_object_[i], nearest_material_[i])) {
    nearest_depth_[i] = depth;
    nearest_object_[i] = s.object;
    nearest_material_[i] = s.material;
  }
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

void Film::merge(const Film& other) {
  if (other.width_ != width_ || other.height_ != height_ || !(other.aovs_ == aovs_))
    throw std::invalid_argument("films of different sizes or AOVs cannot be merged");
  for (size_t i = 0; i < pixels_.size(); ++i) {
    Pixel& a = pixels_[i];
    const Pixel& b = other.pixels_[i];
    for (int c = 0; c < 4; ++c) a.sum[c] += b.sum[c];
    for (int c = 0; c < 3; ++c) a.sum_sq[c] += b.sum_sq[c];
    a.count += b.count;
    // The same order as add_aov_sample: the result does not depend on how samples were split.
    if (tracks_nearest()) {
      if (std::tuple(other.nearest_depth_[i], other.nearest_object_[i], other.nearest_material_[i]) <
          std::tuple(nearest_depth_[i], nearest_object_[i], nearest_material_[i])) {
        nearest_depth_[i] = other.nearest_depth_[i];
        nearest_object_[i] = other.nearest_object_[i];
        nearest_material_[i] = other.nearest_material_[i];
      }
    }
    for (auto [mine, theirs] : {std::pair(&crypto_objects_, &other.crypto_objects_),
                                std::pair(&crypto_materials_, &other.crypto_materials_)}) {
      if (mine->empty()) continue;
      for (const IdCount& c : (*theirs)[i]) add_id_count((*mine)[i], c.id, c.count);
    }
  }
  for (size_t i = 0; i < average_sums_.size(); ++i) average_sums_[i] += other.average_sums_[i];
}

}  // namespace prism
