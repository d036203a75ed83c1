#include "tests/eval/image_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace reenact::eval {
namespace {

ImageGray8 RectMask(int w, int h, int x0, int y0, int x1, int y1) {
  ImageGray8 m(w, h, 1, 0);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) m.at(x, y) = 255;
  return m;
}

TEST(ImageMetrics, IdenticalImagesArePerfect) {
  ImageRgb8 img(64, 48, 3, 0);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c)
        img.at(x, y, c) = static_cast<uint8_t>((x * 3 + y * 5 + c * 40) % 256);
  const ImageGray8 mask = RectMask(64, 48, 10, 10, 40, 30);
  const SubjectComparison c = CompareSubject(img, mask, img, mask);
  EXPECT_TRUE(std::isinf(c.psnr_db));
  EXPECT_NEAR(c.ssim, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(c.iou, 1.0);
  EXPECT_DOUBLE_EQ(c.colour_mae, 0.0);
  EXPECT_EQ(c.union_pixels, 30 * 20);
}

TEST(ImageMetrics, ConstantOffsetGivesPsnrByFormula) {
  const ImageGray8 mask = RectMask(64, 48, 8, 8, 56, 40);  // the box is the mask itself
  const ImageRgb8 a(64, 48, 3, 100), b(64, 48, 3, 110);
  const SubjectComparison c = CompareSubject(a, mask, b, mask);
  EXPECT_NEAR(c.psnr_db, 10 * std::log10(255.0 * 255.0 / 100.0), 1e-9);  // 28.13 dB
  EXPECT_NEAR(c.colour_mae, 10.0, 1e-12);
  EXPECT_LT(c.ssim, 1.0);
}

TEST(ImageMetrics, IouOfShiftedRectangles) {
  const ImageRgb8 img(64, 48, 3, 50);
  // 20x20 squares overlapping in a 10x20 band: IoU = 200 / 600.
  const SubjectComparison c =
      CompareSubject(img, RectMask(64, 48, 10, 10, 30, 30), img, RectMask(64, 48, 20, 10, 40, 30));
  EXPECT_NEAR(c.iou, 200.0 / 600.0, 1e-12);
  EXPECT_DOUBLE_EQ(c.colour_mae, 0.0);
  EXPECT_LT(c.psnr_db, 20.0);  // missing and extra pixels count against the picture
}

TEST(ImageMetrics, DisjointAndEmptySilhouettesAreDefined) {
  const ImageRgb8 img(32, 32, 3, 50);
  const SubjectComparison disjoint =
      CompareSubject(img, RectMask(32, 32, 0, 0, 8, 8), img, RectMask(32, 32, 20, 20, 28, 28));
  EXPECT_DOUBLE_EQ(disjoint.iou, 0.0);
  EXPECT_DOUBLE_EQ(disjoint.colour_mae, 0.0);
  EXPECT_TRUE(std::isfinite(disjoint.psnr_db));
  const ImageGray8 empty(32, 32, 1, 0);
  const SubjectComparison none = CompareSubject(img, empty, img, empty);
  EXPECT_DOUBLE_EQ(none.iou, 1.0);
  EXPECT_EQ(none.union_pixels, 0);
}

TEST(ImageMetrics, UnionBoxSpansBothSilhouettes) {
  const PixelBox box = UnionBox(RectMask(64, 48, 10, 12, 20, 30), RectMask(64, 48, 15, 5, 40, 20));
  EXPECT_EQ(box.x, 10);
  EXPECT_EQ(box.y, 5);
  EXPECT_EQ(box.width, 30);   // columns 10..39
  EXPECT_EQ(box.height, 25);  // rows 5..29
  const ImageGray8 empty(64, 48, 1, 0);
  EXPECT_TRUE(UnionBox(empty, empty).empty());
  EXPECT_THROW(UnionBox(empty, ImageGray8(10, 10, 1, 0)), CheckError);
}

}  // namespace
}  // namespace reenact::eval
