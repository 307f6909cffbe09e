#include "core/work_split.h"

#include <cmath>
#include <limits>

namespace prism {

namespace {

// Boundary i of n equal shares of `total`: floor(i * total / n). Exact while i * total < 2^64,
// which holds for the counts split here (spp up to 2^30, pixels up to 2^16, i <= n <= 2^31).
uint64_t share_boundary(uint64_t total, uint64_t i, uint64_t n) { return i * total / n; }

}  // namespace

std::vector<SampleRange> split_samples(uint64_t spp, int parts) {
  std::vector<SampleRange> ranges;
  if (parts < 1 || uint64_t(parts) > spp) return ranges;
  for (int k = 0; k < parts; ++k) {
    const uint64_t a = share_boundary(spp, uint64_t(k), uint64_t(parts));
    const uint64_t b = share_boundary(spp, uint64_t(k) + 1, uint64_t(parts));
    ranges.push_back({a, b - a});
  }
  return ranges;
}

std::vector<PixelWindow> split_tiles(int width, int height, int parts) {
  std::vector<PixelWindow> tiles;
  if (parts < 1 || width < 1 || height < 1 || int64_t(parts) > int64_t(width) * height) return tiles;
  // Among the factorisations columns x rows = parts that fit the image, the one whose tiles have
  // the aspect ratio nearest 1 (compared in log space, so 2:1 and 1:2 are equally far).
  int best_columns = 0;
  double best_score = std::numeric_limits<double>::infinity();
  for (int columns = 1; columns <= parts; ++columns) {
    if (parts % columns != 0) continue;
    const int rows = parts / columns;
    if (columns > width || rows > height) continue;
    const double aspect = (double(width) / columns) / (double(height) / rows);
    const double score = std::abs(std::log(aspect));
    if (score < best_score) {
      best_score = score;
      best_columns = columns;
    }
  }
  if (best_columns == 0) return tiles;  // e.g. 7 parts of a 3x3 image: no grid fits
  const int columns = best_columns, rows = parts / columns;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c)
      tiles.push_back({int(share_boundary(uint64_t(width), uint64_t(c), uint64_t(columns))),
                       int(share_boundary(uint64_t(height), uint64_t(r), uint64_t(rows))),
                       int(share_boundary(uint64_t(width), uint64_t(c) + 1, uint64_t(columns))),
                       int(share_boundary(uint64_t(height), uint64_t(r) + 1, uint64_t(rows)))});
  return tiles;
}

std::vector<std::vector<size_t>> split_frames(size_t count, int parts) {
  std::vector<std::vector<size_t>> groups;
  if (parts < 1 || size_t(parts) > count) return groups;
  for (int k = 0; k < parts; ++k) {
    std::vector<size_t>& g = groups.emplace_back();
    for (uint64_t i = share_boundary(count, uint64_t(k), uint64_t(parts)); i < share_boundary(count, uint64_t(k) + 1, uint64_t(parts)); ++i)
      g.push_back(size_t(i));
  }
  return groups;
}

}  // namespace prism
