#pragma once
// An axis-aligned pixel rectangle [x0, x1) x [y0, y1).

#include <algorithm>

namespace reenact::capture {

struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool Contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  // Grown by `by` pixels on every side and clipped to a width x height image.
  PixelRect Grown(int by, int width, int height) const {
    return {std::max(0, x0 - by), std::max(0, y0 - by), std::min(width, x1 + by),
            std::min(height, y1 + by)};
  }
};

}  // namespace reenact::capture
