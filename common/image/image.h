#pragma once
// A minimal owning image for common/ (which may not use OpenCV): row-major, interleaved
// channels, pixel (x, y) with x to the right and y down, origin at the top-left pixel.

#include <cstdint>
#include <vector>

#include "common/error/check.h"

namespace reenact {

template <typename T>
struct Image {
  int width = 0;
  int height = 0;
  int channels = 1;
  std::vector<T> data;

  Image() = default;
  Image(int w, int h, int c = 1, T fill = T{}) : width(w), height(h), channels(c) {
    REENACT_CHECK(w >= 0 && h >= 0 && c >= 1, "bad image size");
    data.assign(static_cast<size_t>(w) * h * c, fill);
  }

  bool empty() const { return width == 0 || height == 0; }
  bool Contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  T& at(int x, int y, int c = 0) {
    return data[(static_cast<size_t>(y) * width + x) * channels + c];
  }
  const T& at(int x, int y, int c = 0) const {
    return data[(static_cast<size_t>(y) * width + x) * channels + c];
  }
};

using ImageRgb8 = Image<uint8_t>;     // channels == 3, R G B order
using ImageGray8 = Image<uint8_t>;    // channels == 1 (masks: 0 background, 255 subject)
using ImageDepthMm = Image<uint16_t>; // channels == 1, millimetres, 0 = no reading
using ImageLabel8 = Image<uint8_t>;   // channels == 1, body-part labels (see skeleton.h)

}  // namespace reenact
