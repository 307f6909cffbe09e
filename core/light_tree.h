// LightTree: a bounding hierarchy over lights that picks one for a shading point in proportion to
// how much each branch can light it (Conty Estevez & Kulla 2018; pbrt-v4's BVHLightSampler).
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "core/light_bounds.h"

namespace prism {

class LightTree {
 public:
  LightTree() = default;
  // items[k] bounds light k; lights without power are left out (never picked, pmf 0).
  explicit LightTree(const std::vector<LightBounds>& items);

  bool empty() const { return nodes_.empty(); }
  double power() const { return power_; }

  struct Pick {
    int item = -1;
    float pmf = 0;  // probability of choosing this item at this point
  };
  // Walks down from the root choosing each child by importance at point p with normal n (zero:
  // no surface), reusing u; nothing when no light can reach p.
  std::optional<Pick> sample(const Vec3& p, const Vec3& n, float u) const;
  // The probability that sample(p, n, .) picks `item`.
  float pmf(int item, const Vec3& p, const Vec3& n) const;
  int depth() const { return depth_; }

 private:
  struct Node {
    LightImportance importance;
    int32_t right = -1;  // interior: the second child (the first follows this node); leaf: -1
    int32_t first = -1;  // leaf: its lights are slots first .. first + count - 1
    int32_t count = 0;
  };
  struct BuildItem;
  // Builds the subtree over lights[begin, end) as node nodes_.size(); returns its bounds.
  LightBounds build(std::vector<BuildItem>& lights, size_t begin, size_t end, int parent, int depth);
  // Picks among a leaf's lights by power; returns the slot and its probability.
  std::pair<int, float> pick_in_leaf(const Node& leaf, float u) const;
  // The share of `slot` among the lights of `leaf`, which holds it.
  float slot_probability(const Node& leaf, int slot) const {
    return static_cast<float>(slot_cdf_[size_t(slot)] - (slot == leaf.first ? 0.0 : slot_cdf_[size_t(slot) - 1]));
  }
  // The probability of going to the first child of interior node `node`; negative when neither
  // child can light p.
  float first_child_probability(const Node& node, int index, const Vec3& p, const Vec3& n) const;

  std::vector<Node> nodes_;
  std::vector<int32_t> parent_;   // per node; -1 for the root
  std::vector<int32_t> leaf_of_;  // item -> its leaf node, or -1
  std::vector<int32_t> slot_of_;  // item -> its slot
  // Per slot: the light, and the cumulative share of its leaf's power up to and including it (1
  // for the leaf's last).
  std::vector<int32_t> slot_item_;
  std::vector<double> slot_cdf_;
  int depth_ = 0;
  double power_ = 0;  // of all the lights
};

}  // namespace prism
