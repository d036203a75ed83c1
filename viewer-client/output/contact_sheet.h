#pragma once
// A contact sheet: frames scaled to thumbnails in a grid, each labelled with its number.
//
// Layout (pixels): thumbnails are thumb_width wide and
// thumb_height = max(1, round(frame height * thumb_width / frame width)) tall; with
// c = min(columns, frame count) columns and r = ceil(count / c) rows the sheet is
// c * thumb_width + (c + 1) * kContactSheetGap wide and r * thumb_height + (r + 1) * gap tall.
// Frame i sits at column i % c, row i / c, its top-left pixel at
// (gap + col * (thumb_width + gap), gap + row * (thumb_height + gap)). Gaps have
// kContactSheetBackground. The label (white digits on a black box) covers the thumbnail's
// top-left corner.

#include <array>
#include <cstdint>
#include <vector>

#include "common/image/image.h"

namespace reenact::viewer {

inline constexpr int kContactSheetGap = 4;
inline constexpr std::array<uint8_t, 3> kContactSheetBackground = {24, 24, 24};  // RGB

// Preconditions (CHECK): frames non-empty, all RGB of one size; columns >= 1;
// thumb_width >= 1; frame_numbers empty (labels 0, 1, ...) or one per frame.
ImageRgb8 MakeContactSheet(const std::vector<ImageRgb8>& frames, int columns, int thumb_width,
                           const std::vector<int>& frame_numbers = {});

}  // namespace reenact::viewer
