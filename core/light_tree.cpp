#include "core/light_tree.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>

#include "core/distribution_1d.h"
#include "core/parallel_pair.h"

namespace prism {
namespace {

constexpr int kBuckets = 12;
// Past this depth splits halve by count, so a pathological spread of lights cannot make the tree
// (and the builder's recursion) as deep as it is long.
constexpr int kMaxSahDepth = 48;
// Above this many lights a node halves by count along its widest spread without the cost search,
// which still shapes every subtree below this size. Only emissive meshes of tens of thousands of
// triangles reach it; its effect on their noise is not measured (docs/PERFORMANCE.md).
constexpr size_t kMaxSahLights = 16384;
// From this many lights a node builds its two subtrees in parallel.
constexpr size_t kParallelLights = 65536;

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

// cos(angle(axis, c.w) + c's half-angle): the widest angle from unit `axis` to a direction of c,
// by the angle-sum identity; -1 once it passes pi.
float cos_widest_from(const Vec3& axis, const DirectionCone& c) {
  const float cos_a = std::clamp(dot(axis, c.w), -1.0f, 1.0f), cos_b = c.cos_theta;
  if (cos_a < -cos_b) return -1.0f;
  // A single direction (an emissive triangle's normal): the formula's value exactly, without its
  // two square roots, which the split search would take for every light, axis and level.
  if (cos_b == 1.0f) return cos_a;
  const float sin_a = std::sqrt(std::max(0.0f, 1 - cos_a * cos_a)), sin_b = std::sqrt(std::max(0.0f, 1 - cos_b * cos_b));
  return cos_a * cos_b - sin_a * sin_b;
}

// A cone holding both about their mean axis: wider than cone_union's smallest one, but found with
// no inverse trigonometry. The split search prices thousands of candidate groups with it.
DirectionCone loose_union(const DirectionCone& a, const DirectionCone& b) {
  const Vec3 sum = a.w + b.w;
  const float len = length(sum);
  if (!(len > 0) || a.cos_theta <= -1.0f || b.cos_theta <= -1.0f) return DirectionCone::every_direction();
  const Vec3 axis = sum / len;
  return {axis, std::min(cos_widest_from(axis, a), cos_widest_from(axis, b))};
}

// A bucket of the split search, with a cone in the spirit of loose_union: centred on its lights'
// mean normal and widened to hold each one's cone. It only prices a split; the tree's own bounds
// are merged exactly.
struct Bucket {
  Bounds3 box;
  double power = 0;
  Vec3 axis_sum;
  Vec3 axis;  // axis_sum normalised by finish_adding()
  float cos_emit = 1;
  float cos_theta = 1;
  bool two_sided = false;

  void add(const LightBounds& b) {
    box.extend(b.box);
    power += b.power;
    axis_sum += b.normals.w;
    cos_emit = std::min(cos_emit, b.cos_emit);
    two_sided = two_sided || b.two_sided;
  }
  void finish_adding() {
    const float len = length(axis_sum);
    if (len > 0) axis = axis_sum / len;
    else cos_theta = -1;
  }
  // After finish_adding(): widens the cone about the mean normal to hold b's cone.
  void hold(const LightBounds& b) {
    if (cos_theta > -1.0f) cos_theta = std::min(cos_theta, cos_widest_from(axis, b.normals));
  }
  LightBounds bounds() const {
    LightBounds b;
    if (!(power > 0)) return b;
    b.box = box;
    b.normals = cos_theta > -1.0f ? DirectionCone{axis, cos_theta} : DirectionCone::every_direction();
    b.cos_emit = cos_emit;
    b.power = power;
    b.two_sided = two_sided;
    return b;
  }
};

// Lights the importance function cannot tell apart (the two triangles of an axis-aligned quad):
// splitting them would only choose by power, at the cost of evaluating both.
bool same_bounds(const LightBounds& a, const LightBounds& b) {
  return a.box.lo == b.box.lo && a.box.hi == b.box.hi && a.normals.w == b.normals.w &&
         a.normals.cos_theta == b.normals.cos_theta && a.cos_emit == b.cos_emit && a.two_sided == b.two_sided;
}

}  // namespace

struct LightTree::BinaryNode {
  LightImportance importance;
  int32_t right = -1;  // interior: the second child (the first follows this node); leaf: -1
  int32_t first = -1;  // its lights are slots first .. first + count - 1 (depth first order)
  int32_t count = 0;
};

// A light as the builder moves it around: kept together so each level reads memory in order.
struct LightTree::BuildItem {
  LightBounds bounds;
  Vec3 centroid;
  int item;
};

LightTree::LightTree(std::vector<LightBounds> items) {
  slot_of_.assign(items.size(), -1);
  std::vector<BuildItem> lights;
  lights.reserve(items.size());
  for (size_t k = 0; k < items.size(); ++k)
    if (items[k].power > 0 && std::isfinite(items[k].power)) {
      lights.push_back({items[k], items[k].box.center(), static_cast<int>(k)});
      power_ += items[k].power;
    }
  // Each phase frees what the next does not read, so that for a million emissive triangles the
  // build's peak holds two of its arrays, not four: the items once copied, the build's copies once
  // the binary hierarchy holds their bounds, and the binary hierarchy once collapsed.
  std::vector<LightBounds>().swap(items);
  if (lights.empty()) return;
  std::vector<BinaryNode> binary(2 * lights.size() - 1);
  slot_item_.assign(lights.size(), -1);
  slot_cdf_.assign(lights.size(), 0.0);
  build(binary, 0, lights, 0, lights.size(), 0);
  std::vector<BuildItem>().swap(lights);
  // Counted first: growing the vector instead would copy (and fault in) it several times, and
  // reserving a bound would hold address space (a node per interior binary node) it never uses.
  groups_.reserve(count_groups(binary, 0));
  collapse(binary, 0);
}

int LightTree::open_node(const std::vector<BinaryNode>& binary, int b, int (&kids)[kWidth]) {
  kids[0] = b;
  int n = 1;
  while (n < kWidth) {
    int open = -1;
    for (int k = 0; k < n; ++k)
      if (binary[size_t(kids[k])].right >= 0 &&
          (open < 0 || binary[size_t(kids[k])].importance.power() > binary[size_t(kids[open])].importance.power()))
        open = k;
    if (open < 0) break;
    const int opened = kids[open];
    kids[open] = opened + 1;
    kids[n++] = binary[size_t(opened)].right;
  }
  // In slot order (nodes are numbered depth first, like the slots): pmf() finds a slot's child by
  // walking the ranges in turn.
  std::sort(kids, kids + n);
  return n;
}

size_t LightTree::count_groups(const std::vector<BinaryNode>& binary, int b) {
  int kids[kWidth];
  const int n = open_node(binary, b, kids);
  size_t count = size_t(groups_for(n));
  for (int k = 0; k < n; ++k)
    if (binary[size_t(kids[k])].right >= 0) count += count_groups(binary, kids[k]);
  return count;
}

int32_t LightTree::collapse(const std::vector<BinaryNode>& binary, int b) {
  int kids[kWidth];
  const int n = open_node(binary, b, kids);
  const int32_t index = static_cast<int32_t>(groups_.size());
  groups_.resize(groups_.size() + size_t(groups_for(n)));
  groups_[size_t(index)].children = n;
  for (int k = 0; k < n; ++k) {
    const BinaryNode& kid = binary[size_t(kids[k])];
    const int32_t next = kid.right >= 0 ? collapse(binary, kids[k]) : -1;  // may move groups_
    Group& group = groups_[size_t(index + k / kLanes)];
    const int lane = k % kLanes;
    group.importance.set(lane, kid.importance);
    group.next[lane] = next;
    group.first[lane] = kid.first;
    group.count[lane] = kid.count;
  }
  return index;
}

// A subtree of n lights has at most 2 n - 1 nodes, so each child's place follows from the light
// counts alone: the first child right after its parent, the second after the first's room. The
// nodes are numbered depth first, as the slots are, with gaps where a subtree ended in a leaf of
// lights alike; nothing refers to those. Nothing is placed by the order of the work either, so
// the two subtrees of a large node are built in parallel and the tree does not depend on threads.
LightBounds LightTree::build(std::vector<BinaryNode>& binary, size_t at, std::vector<BuildItem>& lights,
                             size_t begin, size_t end, int depth) {
  // Subtrees keep their lights where the partitions above left them: light k is slot k.
  binary[at].first = static_cast<int32_t>(begin);
  binary[at].count = static_cast<int32_t>(end - begin);
  bool alike = true;
  for (size_t k = begin + 1; k < end && alike; ++k) alike = same_bounds(lights[begin].bounds, lights[k].bounds);
  if (alike) {
    BinaryNode& leaf = binary[at];
    LightBounds all = lights[begin].bounds;
    double leaf_power = 0;
    for (size_t k = begin; k < end; ++k) leaf_power += lights[k].bounds.power;
    all.power = leaf_power;
    leaf.importance = LightImportance(all, 1.0 / power_);
    double cumulative = 0;
    for (size_t k = begin; k < end; ++k) {
      const int item = lights[k].item;
      cumulative += lights[k].bounds.power;
      slot_of_[size_t(item)] = static_cast<int32_t>(k);
      slot_item_[k] = item;
      slot_cdf_[k] = k + 1 == end ? 1.0 : cumulative / leaf_power;
    }
    std::atomic_ref<int> deepest(depth_);  // subtrees may be built on other threads
    for (int seen = deepest.load(std::memory_order_relaxed);
         seen < depth && !deepest.compare_exchange_weak(seen, depth, std::memory_order_relaxed);) {
    }
    return all;
  }
  Bounds3 centroids, box;
  for (size_t k = begin; k < end; ++k) {
    centroids.extend(lights[k].centroid);
    box.extend(lights[k].bounds.box);
  }
  // Binned search over the three axes for the cheapest plane (Conty Estevez & Kulla sec. 4.3).
  const Vec3 extent = centroids.diagonal();
  const float longest = max_component(box.diagonal());
  const int buckets = static_cast<int>(std::min<size_t>(kBuckets, end - begin));
  double best_cost = std::numeric_limits<double>::infinity();
  int best_axis = -1, best_bucket = -1;
  auto bucket_of = [&](const BuildItem& light, int axis) {
    const float t = (light.centroid[axis] - centroids.lo[axis]) / extent[axis];
    return std::clamp(static_cast<int>(t * float(buckets)), 0, buckets - 1);
  };
  // Up to four lights are halved by count: the search would cost more than it can change.
  if (depth < kMaxSahDepth && end - begin > 4 && end - begin <= kMaxSahLights) {
    // All three axes' buckets in one pass over the lights, then their cones in a second. The
    // arrays are reused (the search ends before the recursion) and only buckets in use are
    // reset: most nodes hold a few lights.
    thread_local std::array<std::array<Bucket, kBuckets>, 3> bucket;
    thread_local std::array<LightBounds, kBuckets> below, above;  // entries 1 .. buckets - 1 are set
    for (auto& axis_buckets : bucket)
      for (int b = 0; b < buckets; ++b) axis_buckets[size_t(b)] = Bucket{};
    auto sweep = [&](auto&& visit) {
      for (size_t k = begin; k < end; ++k)
        for (int axis = 0; axis < 3; ++axis)
          if (extent[axis] > 0) visit(bucket[size_t(axis)][size_t(bucket_of(lights[k], axis))], lights[k].bounds);
    };
    sweep([](Bucket& b, const LightBounds& l) { b.add(l); });
    for (auto& axis_buckets : bucket)
      for (int b = 0; b < buckets; ++b) axis_buckets[size_t(b)].finish_adding();
    sweep([](Bucket& b, const LightBounds& l) { b.hold(l); });
    for (int axis = 0; axis < 3; ++axis) {
      if (!(extent[axis] > 0)) continue;
      const std::array<Bucket, kBuckets>& in = bucket[size_t(axis)];
      // Bounds of buckets [0, s) and [s, buckets), built up from either end.
      below[0] = LightBounds{};
      for (int b = 1; b < buckets; ++b)
        below[size_t(b)] = merge(below[size_t(b - 1)], in[size_t(b - 1)].bounds(), loose_union);
      above[size_t(buckets - 1)] = in[size_t(buckets - 1)].bounds();
      for (int b = buckets - 2; b >= 1; --b)
        above[size_t(b)] = merge(above[size_t(b + 1)], in[size_t(b)].bounds(), loose_union);
      const float axis_extent = box.diagonal()[axis];
      const float k_r = axis_extent > 0 ? longest / axis_extent : 1.0f;
      for (int split = 1; split < buckets; ++split) {
        if (!(below[size_t(split)].power > 0) || !(above[size_t(split)].power > 0)) continue;
        const double cost = split_cost(below[size_t(split)], k_r) + split_cost(above[size_t(split)], k_r);
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
    const auto split = std::partition(lights.begin() + std::ptrdiff_t(begin), lights.begin() + std::ptrdiff_t(end),
                                      [&](const BuildItem& l) { return bucket_of(l, best_axis) < best_bucket; });
    mid = static_cast<size_t>(split - lights.begin());
  } else {
    // Every centre in one place, too deep or too many: halve by count along the widest spread.
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (extent[a] > extent[axis]) axis = a;
    mid = begin + (end - begin) / 2;
    std::nth_element(lights.begin() + std::ptrdiff_t(begin), lights.begin() + std::ptrdiff_t(mid),
                     lights.begin() + std::ptrdiff_t(end),
                     [&](const BuildItem& a, const BuildItem& b) { return a.centroid[axis] < b.centroid[axis]; });
  }
  if (mid == begin || mid == end) mid = begin + (end - begin) / 2;
  const size_t left_at = at + 1, right_at = at + 2 * (mid - begin);
  LightBounds first, second;
  if (end - begin < kParallelLights) {
    first = build(binary, left_at, lights, begin, mid, depth + 1);
    second = build(binary, right_at, lights, mid, end, depth + 1);
  } else {
    parallel_pair([&] { first = build(binary, left_at, lights, begin, mid, depth + 1); },
                  [&] { second = build(binary, right_at, lights, mid, end, depth + 1); });
  }
  const LightBounds all = merge(first, second);
  binary[at].right = static_cast<int32_t>(right_at);
  binary[at].importance = LightImportance(all, 1.0 / power_);
  return all;
}

// Unused lanes are judged too (they come to 0). The sums are pairwise, group by group, both ways.
float LightTree::judge(int node, const Vec3& p, const Vec3& n, float importance[kWidth]) const {
  const int groups = groups_for(groups_[size_t(node)].children);
  if (groups == 2 && eight_lanes_)
    return evaluate_pair(groups_[size_t(node)].importance, groups_[size_t(node) + 1].importance, p, n, importance);
  return judge_by_fours(node, groups, p, n, importance);
}

// Out of line, so that judge() itself stays a test and a jump (no registers to save).
[[gnu::noinline]] float LightTree::judge_by_fours(int node, int groups, const Vec3& p, const Vec3& n,
                                                   float importance[kWidth]) const {
  float sum = 0;
  for (int g = 0; g < groups; ++g) {
    float* four = importance + kLanes * g;
    groups_[size_t(node + g)].importance.evaluate(p, n, four);
    sum += (four[0] + four[1]) + (four[2] + four[3]);
  }
  return sum;
}

std::pair<int, float> LightTree::pick_in_leaf(int first, int count, float& u) const {
  // The first slot whose cumulative share exceeds u; the last one's is 1, above every u.
  const auto begin = slot_cdf_.begin() + first, last = begin + (count - 1);
  const int slot = static_cast<int>(std::upper_bound(begin, last, double(u)) - slot_cdf_.begin());
  const double below = slot_start(first, slot), share = slot_cdf_[size_t(slot)] - below;
  u = rescale_to_unit(u, below, share);
  return {slot, static_cast<float>(share)};
}

// One level of a walk: judges the children of the walk's node and moves into the one u chooses,
// or stops at a leaf (Step::Leaf, its lights in w.first, w.count) or where no light reaches p.
[[gnu::always_inline]] inline LightTree::Step LightTree::descend(Walk& w, const Vec3& p, const Vec3& n) const {
  const int children = groups_[size_t(w.node)].children;
  int k = 0;
  // A root leaf (one light, or lights alike) is not judged: it is picked wherever it is, as in
  // sampling by power; what cannot reach p then contributes nothing.
  if (children > 1) {
    float importance[kWidth];
    const float sum = judge(w.node, p, n, importance);
    if (!(sum > 0)) return Step::None;
    // The child whose share of [0, sum) holds u * sum; children of importance 0 are skipped,
    // rounding cannot land on them.
    const float target = w.u * sum;
    float below = 0;
    int last = 0;
    for (int c = 0; c < children; ++c)
      if (importance[c] > 0) last = c;
    k = last;
    for (int c = 0; c < last; ++c) {
      if (importance[c] > 0 && target < below + importance[c]) {
        k = c;
        break;
      }
      below += importance[c];
    }
    w.u = std::clamp((target - below) / importance[k], 0.0f, kOneMinusEpsilon);
    w.pmf *= importance[k] / sum;
  }
  const Group& group = group_of(w.node, k);
  const int lane = k % kLanes;
  if (group.next[lane] < 0) {
    w.first = group.first[lane];
    w.count = group.count[lane];
    return Step::Leaf;
  }
  w.node = group.next[lane];
  return Step::Down;
}

LightTree::Pick LightTree::pick_at_leaf(Walk& w) const {
  const auto [slot, share] = pick_in_leaf(w.first, w.count, w.u);
  return Pick{slot_item_[size_t(slot)], w.pmf * share, w.u};
}

std::optional<LightTree::Pick> LightTree::sample(const Vec3& p, const Vec3& n, float u) const {
  if (groups_.empty()) return std::nullopt;
  Walk w{.u = u};
  for (;;) {
    const Step step = descend(w, p, n);
    if (step == Step::None) return std::nullopt;
    if (step == Step::Leaf) return pick_at_leaf(w);
  }
}

// On a tree of many lights each level of a walk waits for its node to come from memory, and a walk
// is a chain of such waits. Walks taken in turns, each asking for its next node as soon as it knows
// it, wait for their nodes together. Each walk makes the same steps as sample() would.
void LightTree::sample_many(const Vec3* p, const Vec3* n, const float* u, int count, std::optional<Pick>* out) const {
  if (groups_.empty()) {
    std::fill(out, out + count, std::nullopt);
    return;
  }
  constexpr int kBatch = 8;
  if (count > kBatch) {
    for (int first = 0; first < count; first += kBatch)
      sample_many(p + first, n + first, u + first, std::min(count - first, kBatch), out + first);
    return;
  }
  Walk walks[kBatch];
  int active[kBatch], leaves[kBatch];
  int m = count, reached = 0;
  for (int i = 0; i < count; ++i) {
    walks[i].u = u[i];
    active[i] = i;
    out[i] = std::nullopt;
  }
  while (m > 0) {
    int still = 0;
    for (int j = 0; j < m; ++j) {
      const int i = active[j];
      const Step step = descend(walks[i], p[i], n[i]);
      if (step == Step::Down) {
        prefetch_node(walks[i].node);
        active[still++] = i;
      } else if (step == Step::Leaf) {
        // The leaf's cumulative shares, which its pick searches, and its lights.
        const size_t first = size_t(walks[i].first), last = first + size_t(walks[i].count) - 1;
        __builtin_prefetch(&slot_cdf_[first]);
        __builtin_prefetch(&slot_cdf_[last]);
        __builtin_prefetch(&slot_item_[first]);
        __builtin_prefetch(&slot_item_[last]);
        leaves[reached++] = i;
      }
    }
    m = still;
  }
  for (int j = 0; j < reached; ++j) out[leaves[j]] = pick_at_leaf(walks[leaves[j]]);
}

// Every cache line of a node's groups (two at most), ahead of its judging.
void LightTree::prefetch_node(int node) const {
  const size_t groups = std::min<size_t>(2, groups_.size() - size_t(node));
  const char* bytes = reinterpret_cast<const char*>(&groups_[size_t(node)]);
  for (size_t offset = 0; offset < groups * sizeof(Group); offset += 64) __builtin_prefetch(bytes + offset);
}

// The walk sample() makes toward `item`'s slot, with the same numbers in the same order.
float LightTree::pmf(int item, const Vec3& p, const Vec3& n) const {
  if (item < 0 || size_t(item) >= slot_of_.size() || slot_of_[size_t(item)] < 0) return 0;
  const int slot = slot_of_[size_t(item)];
  int index = 0;
  float pmf = 1.0f;
  for (;;) {
    int k = 0;
    while (slot >= group_of(index, k).first[k % kLanes] + group_of(index, k).count[k % kLanes]) ++k;
    if (groups_[size_t(index)].children > 1) {
      float importance[kWidth];
      const float sum = judge(index, p, n, importance);
      if (!(sum > 0) || !(importance[k] > 0)) return 0;
      pmf *= importance[k] / sum;
    }
    const Group& group = group_of(index, k);
    const int lane = k % kLanes;
    if (group.next[lane] < 0) return pmf * slot_probability(group.first[lane], slot);
    index = group.next[lane];
  }
}

}  // namespace prism
