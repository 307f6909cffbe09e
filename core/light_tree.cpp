#include "core/light_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace prism {
namespace {

constexpr int kBuckets = 12;
// Past this depth splits halve by count, so a pathological spread of lights cannot make the tree
// (and the builder's recursion) as deep as it is long.
constexpr int kMaxSahDepth = 48;
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

float surface_area(const Bounds3& b) {
  const Vec3 d = b.diagonal();
  return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// Conty Estevez & Kulla's surface-area-orientation cost of a candidate child (eq. 2), with their
// regularisation against thin slices along a short axis (k_r).
double split_cost(const LightBounds& b, float k_r) {
  if (!(b.power > 0)) return 0;
  return b.power * double(orientation_measure(b)) * double(k_r) * double(surface_area(b.box));
}

// Lights the importance function cannot tell apart (the two triangles of an axis-aligned quad):
// splitting them would only choose by power, at the cost of evaluating both.
bool same_bounds(const LightBounds& a, const LightBounds& b) {
  return a.box.lo == b.box.lo && a.box.hi == b.box.hi && a.normals.w == b.normals.w &&
         a.normals.cos_theta == b.normals.cos_theta && a.cos_emit == b.cos_emit && a.two_sided == b.two_sided;
}

}  // namespace

LightTree::LightTree(const std::vector<LightBounds>& items) {
  leaf_of_.assign(items.size(), -1);
  slot_of_.assign(items.size(), -1);
  std::vector<int> order;
  for (size_t k = 0; k < items.size(); ++k)
    if (items[k].power > 0 && std::isfinite(items[k].power)) order.push_back(static_cast<int>(k));
  if (order.empty()) return;
  for (int k : order) power_ += items[size_t(k)].power;
  nodes_.reserve(2 * order.size() - 1);
  parent_.reserve(2 * order.size() - 1);
  build(order, items, 0, order.size(), -1, 0);
}

int LightTree::build(std::vector<int>& order, const std::vector<LightBounds>& items, size_t begin, size_t end,
                     int parent, int depth) {
  depth_ = std::max(depth_, depth);
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back({});
  parent_.push_back(parent);
  bool alike = true;
  for (size_t k = begin + 1; k < end && alike; ++k) alike = same_bounds(items[order[begin]], items[order[k]]);
  if (alike) {
    Node& leaf = nodes_[size_t(index)];
    LightBounds all = items[order[begin]];
    double leaf_power = 0;
    for (size_t k = begin; k < end; ++k) leaf_power += items[order[k]].power;
    all.power = leaf_power;
    leaf.importance = LightImportance(all, 1.0 / power_);
    leaf.first = static_cast<int32_t>(slot_item_.size());
    leaf.count = static_cast<int32_t>(end - begin);
    double cumulative = 0;
    for (size_t k = begin; k < end; ++k) {
      const int item = order[k];
      cumulative += items[size_t(item)].power;
      leaf_of_[size_t(item)] = index;
      slot_of_[size_t(item)] = static_cast<int32_t>(slot_item_.size());
      slot_item_.push_back(item);
      slot_cdf_.push_back(k + 1 == end ? 1.0 : cumulative / leaf_power);
      slot_first_.push_back(k == begin);
    }
    return index;
  }
  Bounds3 centroids;
  LightBounds all;
  for (size_t k = begin; k < end; ++k) {
    centroids.extend(items[order[k]].box.center());
    all = merge(all, items[order[k]]);
  }
  // Binned search over the three axes for the cheapest plane (Conty Estevez & Kulla sec. 4.3).
  const Vec3 extent = centroids.diagonal();
  const float longest = max_component(all.box.diagonal());
  double best_cost = std::numeric_limits<double>::infinity();
  int best_axis = -1, best_bucket = -1;
  auto bucket_of = [&](int item, int axis) {
    const float t = (items[item].box.center()[axis] - centroids.lo[axis]) / extent[axis];
    return std::clamp(static_cast<int>(t * kBuckets), 0, kBuckets - 1);
  };
  if (depth < kMaxSahDepth) {
    for (int axis = 0; axis < 3; ++axis) {
      if (!(extent[axis] > 0)) continue;
      std::array<LightBounds, kBuckets> bucket{};
      for (size_t k = begin; k < end; ++k) {
        LightBounds& b = bucket[size_t(bucket_of(order[k], axis))];
        b = merge(b, items[order[k]]);
      }
      const float axis_extent = all.box.diagonal()[axis];
      const float k_r = axis_extent > 0 ? longest / axis_extent : 1.0f;
      for (int split = 1; split < kBuckets; ++split) {
        LightBounds below, above;
        for (int b = 0; b < split; ++b) below = merge(below, bucket[size_t(b)]);
        for (int b = split; b < kBuckets; ++b) above = merge(above, bucket[size_t(b)]);
        if (!(below.power > 0) || !(above.power > 0)) continue;
        const double cost = split_cost(below, k_r) + split_cost(above, k_r);
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_bucket = split;
        }
      }
    }
  }
  size_t mid;
  if (best_axis >= 0) {
    const auto split = std::partition(order.begin() + std::ptrdiff_t(begin), order.begin() + std::ptrdiff_t(end),
                                      [&](int item) { return bucket_of(item, best_axis) < best_bucket; });
    mid = static_cast<size_t>(split - order.begin());
  } else {
    // Every centre in one place, or too deep: halve by count along the widest spread.
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (extent[a] > extent[axis]) axis = a;
    mid = begin + (end - begin) / 2;
    std::nth_element(order.begin() + std::ptrdiff_t(begin), order.begin() + std::ptrdiff_t(mid),
                     order.begin() + std::ptrdiff_t(end),
                     [&](int a, int b) { return items[a].box.center()[axis] < items[b].box.center()[axis]; });
  }
  if (mid == begin || mid == end) mid = begin + (end - begin) / 2;
  build(order, items, begin, mid, index, depth + 1);
  const int right = build(order, items, mid, end, index, depth + 1);
  nodes_[index].right = right;
  nodes_[index].importance = LightImportance(all, 1.0 / power_);
  return index;
}

float LightTree::first_child_probability(const Node& node, int index, const Vec3& p, const Vec3& n) const {
  const float first = nodes_[size_t(index) + 1].importance(p, n);
  const float second = nodes_[size_t(node.right)].importance(p, n);
  const float sum = first + second;
  if (!(sum > 0)) return -1.0f;
  return first / sum;
}

std::pair<int, float> LightTree::pick_in_leaf(const Node& leaf, float u) const {
  // The first slot whose cumulative share exceeds u; the last one's is 1, above every u.
  const auto begin = slot_cdf_.begin() + leaf.first, last = begin + (leaf.count - 1);
  const int slot = static_cast<int>(std::upper_bound(begin, last, double(u)) - slot_cdf_.begin());
  return {slot, slot_probability(slot)};
}

std::optional<LightTree::Pick> LightTree::sample(const Vec3& p, const Vec3& n, float u) const {
  if (nodes_.empty()) return std::nullopt;
  int index = 0;
  float pmf = 1.0f;
  while (nodes_[size_t(index)].right >= 0) {
    const Node& node = nodes_[size_t(index)];
    const float p_first = first_child_probability(node, index, p, n);
    if (p_first < 0) return std::nullopt;
    if (u < p_first) {
      u = std::min(u / p_first, kOneMinusEpsilon);
      pmf *= p_first;
      index = index + 1;
    } else {
      u = std::min((u - p_first) / (1.0f - p_first), kOneMinusEpsilon);
      pmf *= 1.0f - p_first;
      index = node.right;
    }
  }
  // A root leaf (one light, or lights alike) is not judged: it is picked wherever it is, as in
  // sampling by power; what cannot reach p then contributes nothing.
  const auto [slot, share] = pick_in_leaf(nodes_[size_t(index)], u);
  return Pick{slot_item_[size_t(slot)], pmf * share};
}

float LightTree::pmf(int item, const Vec3& p, const Vec3& n) const {
  if (item < 0 || size_t(item) >= leaf_of_.size() || leaf_of_[size_t(item)] < 0) return 0;
  int index = leaf_of_[size_t(item)];
  float pmf = slot_probability(slot_of_[size_t(item)]);
  while (index != 0) {
    const int parent = parent_[size_t(index)];
    const float p_first = first_child_probability(nodes_[size_t(parent)], parent, p, n);
    if (p_first < 0) return 0;
    pmf *= index == parent + 1 ? p_first : 1.0f - p_first;
    index = parent;
  }
  return pmf;
}

}  // namespace prism
