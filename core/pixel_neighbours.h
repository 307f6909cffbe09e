// for_each_neighbour: visits the pixels around (x, y) that lie inside the image, for the per-pixel
// estimates that must not see a pixel's own samples.
#pragma once

#include <algorithm>

namespace prism {

// Calls f(nx, ny) for each pixel of the 3x3 block centred on (x, y) inside a width x height image,
// (x, y) itself left out, top row first and left to right within a row (a fixed summation order).
template <class F>
void for_each_neighbour(int x, int y, int width, int height, F&& f) {
  for (int ny = std::max(0, y - 1); ny <= std::min(height - 1, y + 1); ++ny)
    for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx)
      if (nx != x || ny != y) f(nx, ny);
}

}  // namespace prism
