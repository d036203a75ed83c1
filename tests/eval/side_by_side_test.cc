#include "tests/eval/side_by_side.h"

#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact::eval {
namespace {

ImageGray8 RectMask(int w, int h, int x0, int y0, int x1, int y1) {
  ImageGray8 m(w, h, 1, 0);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) m.at(x, y) = 255;
  return m;
}

int Luma(const ImageRgb8& img, int x, int y) {
  return img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2);
}

TEST(SideBySide, PanelsShowTheBoxWithMarginAndGaps) {
  const ImageRgb8 truth(64, 48, 3, 200), rendered(64, 48, 3, 90);
  // Union box: columns 10..39, rows 12..29; margin 2 -> 34 x 22 panels.
  const ImageGray8 tm = RectMask(64, 48, 10, 12, 30, 30), rm = RectMask(64, 48, 20, 12, 40, 30);
  SideBySideOptions options;
  options.margin_px = 2;
  options.gap_px = 3;
  const ImageRgb8 out = SideBySide(truth, tm, rendered, rm, options);
  ASSERT_EQ(out.width, 3 * 34 + 2 * 3);
  ASSERT_EQ(out.height, 22);
  // Panel pixel (x, y) is image pixel (8 + x, 10 + y).
  EXPECT_EQ(out.at(2, 2, 0), 200);       // truth inside its mask
  EXPECT_EQ(out.at(0, 0, 0), 0);         // margin: black
  EXPECT_EQ(out.at(30, 5, 1), 0);        // right of the truth mask: black
  EXPECT_EQ(out.at(34, 5, 2), 128);      // gap: grey
  EXPECT_EQ(out.at(37 + 2, 5, 0), 0);    // rendered panel, left of its mask
  EXPECT_EQ(out.at(37 + 20, 5, 0), 90);  // rendered inside its mask
  // Error panel: black where both are empty, brighter where one image lacks the subject
  // (error 200 or 90) than where both show it (error 110).
  const int ex = 2 * (34 + 3);
  EXPECT_LT(Luma(out, ex + 0, 0), 12);                     // inferno starts at near-black (0, 0, 4)
  EXPECT_GT(Luma(out, ex + 5, 5), Luma(out, ex + 15, 5));  // truth only (200) vs both (110)
  EXPECT_GT(Luma(out, ex + 15, 5), Luma(out, ex + 30, 5));  // both (110) vs rendered only (90)
}

TEST(SideBySide, ErrorsAtAndAboveFullScaleLookAlike) {
  const ImageGray8 mask = RectMask(16, 16, 0, 0, 16, 16);
  ImageRgb8 truth(16, 16, 3, 0);
  const ImageRgb8 rendered(16, 16, 3, 0);
  for (int x = 0; x < 16; ++x)
    for (int c = 0; c < 3; ++c) truth.at(x, 0, c) = static_cast<uint8_t>(x < 8 ? 128 : 255);
  const ImageRgb8 out = SideBySide(truth, mask, rendered, mask);  // margin clamped: 16 x 16
  ASSERT_EQ(out.width, 3 * 16 + 2 * 4);
  const int ex = 2 * (16 + 4);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(out.at(ex + 2, 0, c), out.at(ex + 12, 0, c));
  EXPECT_GT(Luma(out, ex + 2, 0), Luma(out, ex + 2, 1));  // error 128 vs 0
}

TEST(SideBySide, EmptySilhouettesShowTheWholeImage) {
  const ImageGray8 empty(20, 10, 1, 0);
  const ImageRgb8 img(20, 10, 3, 50);
  const ImageRgb8 out = SideBySide(img, empty, img, empty);
  EXPECT_EQ(out.width, 3 * 20 + 2 * 4);
  EXPECT_EQ(out.height, 10);
  EXPECT_EQ(out.at(5, 5, 0), 0);
}

TEST(SideBySide, RejectsMismatchedSizesAndBadOptions) {
  const ImageGray8 m(20, 10, 1, 0);
  const ImageRgb8 img(20, 10, 3, 50), other(21, 10, 3, 50);
  EXPECT_THROW(SideBySide(img, m, other, m), CheckError);
  SideBySideOptions bad;
  bad.error_full_scale = 0;
  EXPECT_THROW(SideBySide(img, m, img, m, bad), CheckError);
  bad = {};
  bad.margin_px = -1;
  EXPECT_THROW(SideBySide(img, m, img, m, bad), CheckError);
}

}  // namespace
}  // namespace reenact::eval
