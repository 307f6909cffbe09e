// LightTree: a bounding hierarchy over lights that picks one for a shading point in proportion to
// how much each branch can light it (Conty Estevez & Kulla 2018; pbrt-v4's BVHLightSampler).
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "core/light_importance.h"

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
    float pmf = 0;      // probability of choosing this item at this point
    float remapped = 0;  // u rescaled to [0, 1) within the item's share of it
  };
  // Walks down from the root choosing each child by importance at point p with normal n (zero:
  // no surface), reusing u; nothing when no light can reach p.
  std::optional<Pick> sample(const Vec3& p, const Vec3& n, float u) const;
  // The probability that sample(p, n, .) picks `item`.
  float pmf(int item, const Vec3& p, const Vec3& n) const;
  // Of the binary hierarchy as built; the walk takes about a third as many steps (see Node).
  int depth() const { return depth_; }

 private:
  // The binary hierarchy is built first (the split search is binary), then collapsed: each node
  // takes up to eight descendants as its children and a pick weighs them by their own, tighter
  // importance instead of multiplying ratios of looser bounds. The walk has a third of the levels,
  // which on a tree of a million lights means fewer cache misses, and the children are judged
  // four at a time in SIMD lanes. Eight children cost what four did and choose better
  // (docs/PERFORMANCE.md, "SIMD importance").
  static constexpr int kWidth = 8;
  static constexpr int kGroups = kWidth / 4;  // of four children, judged in one pass of SIMD lanes
  struct Node {
    LightImportance4 importance[kGroups];  // unused children have no power: importance 0
    int32_t next[kWidth];                  // a child's node, or -1 for a leaf
    int32_t first[kWidth] = {};  // a child's lights are slots first .. first + count - 1
    int32_t count[kWidth] = {};
    int32_t children = 0;        // 1 only for a root that is a leaf: it is not judged
  };
  struct BinaryNode;
  struct BuildItem;
  // Builds the binary subtree over lights[begin, end) as binary.size(); returns its bounds.
  LightBounds build(std::vector<BinaryNode>& binary, std::vector<BuildItem>& lights, size_t begin, size_t end,
                    int depth);
  // Makes up to kWidth descendants of binary node b (the most powerful interior ones opened first)
  // the children of a new node, in slot order; returns its index.
  int32_t collapse(const std::vector<BinaryNode>& binary, int b);
  // Picks among lights [first, first + count) by power; returns the slot and its probability,
  // and rescales u to [0, 1) within the slot's share.
  std::pair<int, float> pick_in_leaf(int first, int count, float& u) const;
  // Where `slot`'s share begins in the cumulative shares of the leaf that starts at `first`.
  double slot_start(int first, int slot) const { return slot == first ? 0.0 : slot_cdf_[size_t(slot) - 1]; }
  // The share of `slot` among the lights of the leaf that starts at `first`, which holds it.
  float slot_probability(int first, int slot) const {
    return static_cast<float>(slot_cdf_[size_t(slot)] - slot_start(first, slot));
  }
  // The children's importance at (p, n) and their sum (not positive when none can light p).
  float judge(const Node& node, const Vec3& p, const Vec3& n, float importance[kWidth]) const;

  std::vector<Node> nodes_;       // the root first
  std::vector<int32_t> slot_of_;  // item -> its slot, or -1
  // Per slot: the light, and the cumulative share of its leaf's power up to and including it (1
  // for the leaf's last).
  std::vector<int32_t> slot_item_;
  std::vector<double> slot_cdf_;
  int depth_ = 0;
  double power_ = 0;  // of all the lights
};

}  // namespace prism
