#pragma once
// PNG files of rendered frames and masks.

#include <string>

#include "common/error/expected.h"
#include "common/image/image.h"

namespace reenact::viewer {

// Writes an 8-bit image with 1 (grey) or 3 (RGB) channels as PNG. Errors: "invalid_argument"
// for an empty image or another channel count, "io" when the file cannot be written (the
// message names the path).
Status WritePng(const std::string& path, const ImageRgb8& image);

}  // namespace reenact::viewer
