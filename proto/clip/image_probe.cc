#include "proto/clip/image_probe.h"

namespace reenact::proto {
namespace {

uint32_t ReadBe(std::span<const uint8_t> b, size_t at, int n) {
  uint32_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | b[at + i];
  return v;
}

bool IsStartOfFrame(uint8_t marker) {
  // SOF0..SOF15 except DHT (C4), JPG (C8) and DAC (CC).
  return marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

}  // namespace

std::optional<ImageProbe> ProbePng(std::span<const uint8_t> b) {
  static constexpr uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (b.size() < 33) return std::nullopt;
  for (int i = 0; i < 8; ++i)
    if (b[i] != kSignature[i]) return std::nullopt;
  if (ReadBe(b, 8, 4) != 13 || b[12] != 'I' || b[13] != 'H' || b[14] != 'D' || b[15] != 'R')
    return std::nullopt;
  const uint32_t width = ReadBe(b, 16, 4), height = ReadBe(b, 20, 4);
  if (width == 0 || height == 0 || width > 0x7FFFFFFF || height > 0x7FFFFFFF) return std::nullopt;
  return ImageProbe{static_cast<int>(width), static_cast<int>(height), b[24], b[25]};
}

std::optional<ImageProbe> ProbeJpeg(std::span<const uint8_t> b) {
  if (b.size() < 4 || b[0] != 0xFF || b[1] != 0xD8) return std::nullopt;
  size_t at = 2;
  while (at + 4 <= b.size()) {
    if (b[at] != 0xFF) return std::nullopt;
    const uint8_t marker = b[at + 1];
    if (marker == 0xFF) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {  // no length field
      at += 2;
      continue;
    }
    if (marker == 0xD9 || marker == 0xDA) return std::nullopt;  // EOI or scan before SOF
    const uint32_t length = ReadBe(b, at + 2, 2);
    if (length < 2 || at + 2 + length > b.size()) return std::nullopt;
    if (IsStartOfFrame(marker)) {
      if (length < 8) return std::nullopt;
      const int precision = b[at + 4];
      const int height = static_cast<int>(ReadBe(b, at + 5, 2));
      const int width = static_cast<int>(ReadBe(b, at + 7, 2));
      const int components = b[at + 9];
      if (width == 0 || height == 0) return std::nullopt;
      return ImageProbe{width, height, precision, components};
    }
    at += 2 + length;
  }
  return std::nullopt;
}

}  // namespace reenact::proto
