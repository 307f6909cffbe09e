// LaneRows: the fields of up to 64 vertices' requests to a SIMD kernel, each field a row of lanes.
#pragma once

#include <algorithm>

#include "core/vec3.h"

namespace prism {

// Written lane by lane as the vertices shade (next_lane, then set), read eight lanes at a time by
// a kernel (integrators/lane_math.h). kRows fields; rows of three hold a vector's x, y and z.
template <int kRows>
class LaneRows {
 public:
  static constexpr int kLanes = 64;  // Integrator::kPathsInLockstep

  int size() const { return size_; }
  void clear() { size_ = 0; }
  const float* row(int r) const { return rows_[r]; }

 protected:
  // A lane's first use of a block of kBlock lanes, which the kernels read whole, fills the block with
  // zeros: lanes past size() then hold finite values (zeros, or an earlier round's), whose results
  // are never read.
  int next_lane() {
    if (size_ % kBlock == 0 && size_ >= written_) [[unlikely]]
      fill_block();
    return size_++;
  }
  void set(int r, int lane, float v) { rows_[r][lane] = v; }
  void set(int r, int lane, const Vec3& v) {
    rows_[r][lane] = v.x;
    rows_[r + 1][lane] = v.y;
    rows_[r + 2][lane] = v.z;
  }

 private:
  static constexpr int kBlock = 8;  // lanes a kernel reads at once (lanes::kLanes)
  // Out of line, so that next_lane stays small enough to inline wherever a lane is added.
  [[gnu::noinline]] void fill_block() {
    for (float* row : rows_) std::fill_n(row + size_, kBlock, 0.0f);
    written_ = size_ + kBlock;
  }
  static_assert(kLanes % kBlock == 0);
  alignas(32) float rows_[kRows][kLanes];
  int size_ = 0;
  int written_ = 0;  // lanes [0, written_) have been filled (next_lane)
};

}  // namespace prism
