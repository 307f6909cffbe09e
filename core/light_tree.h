// LightTree: a bounding hierarchy over lights that picks one for a shading point in proportion to
// how much each branch can light it (Conty Estevez & Kulla 2018; pbrt-v4's BVHLightSampler).
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "core/cpu_features.h"
#include "core/light_importance.h"

namespace prism {

class LightTree {
 public:
  LightTree() = default;
  // items[k] bounds light k; lights without power are left out (never picked, pmf 0). Taken by
  // value so that a caller can move them in: they are freed as soon as the build has copied them.
  explicit LightTree(std::vector<LightBounds> items);

  bool empty() const { return groups_.empty(); }
  double power() const { return power_; }

  struct Pick {
    int item = -1;
    float pmf = 0;      // probability of choosing this item at this point
    float remapped = 0;  // u rescaled to [0, 1) within the item's share of it
  };
  // Walks down from the root choosing each child by importance at point p with normal n (zero:
  // no surface), reusing u; nothing when no light can reach p.
  std::optional<Pick> sample(const Vec3& p, const Vec3& n, float u) const;
  // sample() for each of count shading points (p[i], n[i], u[i]) -> out[i], the same picks, with
  // the walks interleaved so that their cache misses overlap (a packet's lanes on a large tree).
  void sample_many(const Vec3* p, const Vec3* n, const float* u, int count, std::optional<Pick>* out) const;
  // The probability that sample(p, n, .) picks `item`.
  float pmf(int item, const Vec3& p, const Vec3& n) const;
  // Of the binary hierarchy as built; the walk takes about a third as many steps (see Group).
  int depth() const { return depth_; }
  // The memory a walk reads its nodes from.
  size_t node_bytes() const { return groups_.size() * sizeof(Group); }

 private:
  // The binary hierarchy is built first (the split search is binary), then collapsed: each node
  // takes up to eight descendants as its children and a pick weighs them by their own, tighter
  // importance instead of multiplying ratios of looser bounds. The walk has a third of the levels,
  // which on a tree of a million lights means fewer cache misses, and the children are judged
  // four at a time in SSE lanes, or all eight in one AVX2 pass (evaluate_pair). Eight children
  // cost what four did and choose better (docs/PERFORMANCE.md, "SIMD importance").
  //
  // A node is stored as its children's groups of four, one after another: one group when it has
  // up to four children, two when more. A node with four or fewer (near the leaves, where the
  // binary subtree runs out of interior nodes to open) then takes half the memory, and its walk
  // judges the one group only.
  static constexpr int kWidth = 8;
  static constexpr int kLanes = 4;  // children in a group, judged in one pass of SIMD lanes
  struct Group {
    LightImportance4 importance;               // unused lanes have no power: importance 0
    int32_t next[kLanes] = {-1, -1, -1, -1};  // a child's node (its first group), or -1 for a leaf
    int32_t first[kLanes] = {};               // a child's lights are slots first .. first + count - 1
    int32_t count[kLanes] = {};
    int32_t children = 0;  // of the node, in its first group; 1 only for a root that is a leaf (not judged)
  };
  static int groups_for(int children) { return (children + kLanes - 1) / kLanes; }
  // The group holding child k of the node whose first group is `node` (in lane k % kLanes).
  const Group& group_of(int node, int k) const { return groups_[size_t(node + k / kLanes)]; }
  struct BinaryNode;
  struct BuildItem;
  // Builds the binary subtree over lights[begin, end) with its root at binary[at], its nodes within
  // binary[at, at + 2 (end - begin) - 1); returns its bounds.
  LightBounds build(std::vector<BinaryNode>& binary, size_t at, std::vector<BuildItem>& lights, size_t begin,
                    size_t end, int depth);
  // The descendants of binary node b that become the children of its node: b opened, then the most
  // powerful interior one among them again and again, until there are kWidth or all are leaves.
  // Returns how many, in kids, in slot order.
  static int open_node(const std::vector<BinaryNode>& binary, int b, int (&kids)[kWidth]);
  // How many groups collapse(binary, b) makes.
  static size_t count_groups(const std::vector<BinaryNode>& binary, int b);
  // Makes the open_node descendants of binary node b the children of a new node; returns its first group.
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
  // A walk from the root toward one light, a level at a time.
  struct Walk {
    int node = 0;  // the node it is at (its first group)
    float pmf = 1.0f;
    float u = 0;     // the draw, rescaled at each level to the chosen child's share
    int first = -1;  // at a leaf: its lights are slots first .. first + count - 1
    int count = 0;
  };
  enum class Step { Down, Leaf, None };
  Step descend(Walk& w, const Vec3& p, const Vec3& n) const;
  // The light a walk that reached its leaf picks there.
  Pick pick_at_leaf(Walk& w) const;
  void prefetch_node(int node) const;
  // The children's importance at (p, n) and their sum (not positive when none can light p).
  float judge(int node, const Vec3& p, const Vec3& n, float importance[kWidth]) const;
  // judge() four children at a time, one group after the other.
  float judge_by_fours(int node, int groups, const Vec3& p, const Vec3& n, float importance[kWidth]) const;

  std::vector<Group> groups_;     // the nodes' groups, the root's first
  std::vector<int32_t> slot_of_;  // item -> its slot, or -1
  // Per slot: the light, and the cumulative share of its leaf's power up to and including it (1
  // for the leaf's last).
  std::vector<int32_t> slot_item_;
  std::vector<double> slot_cdf_;
  int depth_ = 0;
  double power_ = 0;  // of all the lights
  bool eight_lanes_ = cpu_has_avx2();  // judge() a node's two groups at once (evaluate_pair)
};

}  // namespace prism
