// LaneRows: the fields of up to 32 vertices' requests to a SIMD kernel, each field a row of lanes.
#pragma once

#include "core/vec3.h"

namespace prism {

// Written lane by lane as the vertices shade (next_lane, then set), read eight lanes at a time by
// a kernel (integrators/lane_math.h). kRows fields; rows of three hold a vector's x, y and z.
template <int kRows>
class LaneRows {
 public:
  static constexpr int kLanes = 32;

  int size() const { return size_; }
  void clear() { size_ = 0; }
  const float* row(int r) const { return rows_[r]; }

 protected:
  int next_lane() { return size_++; }
  void set(int r, int lane, float v) { rows_[r][lane] = v; }
  void set(int r, int lane, const Vec3& v) {
    rows_[r][lane] = v.x;
    rows_[r + 1][lane] = v.y;
    rows_[r + 2][lane] = v.z;
  }

 private:
  // Zeros at first: lanes past size() hold finite values, whose results are never read.
  alignas(32) float rows_[kRows][kLanes] = {};
  int size_ = 0;
};

}  // namespace prism
