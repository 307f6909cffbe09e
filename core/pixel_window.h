// PixelWindow: a rectangle of whole pixels [x0, x1) x [y0, y1), for crops and EXR data windows.
#pragma once

namespace prism {

struct PixelWindow {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool contains(const PixelWindow& o) const { return o.x0 >= x0 && o.y0 >= y0 && o.x1 <= x1 && o.y1 <= y1; }
  bool operator==(const PixelWindow&) const = default;
};

}  // namespace prism
