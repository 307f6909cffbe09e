// MediumStack: the nested volumes a path is inside, for the index of refraction on each side of a
// boundary and the absorption along each segment (glass holding liquid, touching dielectrics).
#pragma once

#include <array>

#include "core/scene_desc.h"
#include "materials/medium.h"

namespace prism {

class MediumStack {
 public:
  static constexpr int kMaxDepth = 8;

  bool empty() const { return size_ == 0; }  // outside every volume: nothing absorbs
  // The innermost medium's index of refraction (1 outside every volume) and absorption.
  float ior() const { return size_ ? entries_[size_ - 1].ior : 1.0f; }
  Rgb sigma_a() const { return size_ ? entries_[size_ - 1].sigma_a : Rgb(0.0f); }

  // n_back / n_front at a surface of `m` reached from its front (from_front) or from inside.
  // Volume boundaries separate m from the medium around it (the one below m in the stack when
  // leaving, after Schmidt and Budge, "Simple Nested Dielectrics in Ray Traced Images", 2002);
  // other surfaces see m's IOR against the current medium.
  float interface_eta(const MaterialDesc& m, int material, bool from_front) const {
    if (!m.has_volume() || from_front) return m.ior / ior();
    const int i = find(material);
    const float outside = i > 0 ? entries_[i - 1].ior : (i == 0 ? 1.0f : ior());
    return m.ior / outside;
  }

  // Crossing a volume boundary of material `m`: entering pushes it, leaving removes it.
  void cross(const MaterialDesc& m, int material, bool from_front) {
    if (!m.has_volume()) return;
    if (from_front) {
      if (size_ < kMaxDepth) entries_[size_++] = {material, m.ior, absorption_coefficient(m)};
      return;
    }
    const int i = find(material);
    if (i < 0) return;  // leaving a volume never entered (camera inside, or an open mesh)
    for (int k = i; k + 1 < size_; ++k) entries_[k] = entries_[k + 1];
    --size_;
  }

 private:
  int find(int material) const {
    for (int k = size_ - 1; k >= 0; --k)
      if (entries_[k].material == material) return k;
    return -1;
  }

  struct Entry {
    int material = -1;
    float ior = 1.0f;
    Rgb sigma_a;
  };
  std::array<Entry, kMaxDepth> entries_{};
  int size_ = 0;
};

}  // namespace prism
