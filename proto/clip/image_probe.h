#pragma once
// Reads the size (and PNG pixel format) from an encoded image's header without decoding it,
// so that codecs can reject an image whose stated size disagrees with its container before
// spending memory on it (a small file can claim a huge image).

#include <cstdint>
#include <optional>
#include <span>

namespace reenact::proto {

struct ImageProbe {
  int width = 0;
  int height = 0;
  int bit_depth = 0;   // PNG: bits per sample; JPEG: sample precision
  int color_type = 0;  // PNG colour type (0 grey, 2 RGB, 3 palette, 4 grey+alpha, 6 RGBA);
                       // JPEG: number of components
};

// PNG: signature and IHDR chunk. nullopt if the bytes are not a PNG with an IHDR.
std::optional<ImageProbe> ProbePng(std::span<const uint8_t> bytes);

// JPEG: the first SOFn segment before the first scan. nullopt if none is found.
std::optional<ImageProbe> ProbeJpeg(std::span<const uint8_t> bytes);

}  // namespace reenact::proto
