#include "tests/eval/temporal_flicker.h"

#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact::eval {
namespace {

// A w x h image pair: colour `value` inside the rectangle [x0, x1) x [0, h), mask 255 there.
struct Frame {
  ImageRgb8 color;
  ImageGray8 mask;
};
Frame Box(int x0, int x1, uint8_t value, int w = 20, int h = 10) {
  Frame f{ImageRgb8(w, h, 3, 0), ImageGray8(w, h, 1, 0)};
  for (int y = 0; y < h; ++y)
    for (int x = x0; x < x1; ++x) {
      f.mask.at(x, y) = 255;
      for (int c = 0; c < 3; ++c) f.color.at(x, y, c) = value;
    }
  return f;
}

FlickerMeasure Measure(const Frame& ra, const Frame& rb, const Frame& ta, const Frame& tb) {
  return MeasureFlicker(ra.color, ra.mask, rb.color, rb.mask, ta.color, ta.mask, tb.color, tb.mask);
}

TEST(TemporalFlicker, AReenactmentThatChangesExactlyAsTheTruthHasNoFlicker) {
  // The subject (a box of grey 100) moves 4 px right; the reenactment shows the same.
  const Frame a = Box(2, 10, 100), b = Box(6, 14, 100);
  const FlickerMeasure m = Measure(a, b, a, b);
  // Pixels changed: x in [2, 6) and [10, 14), 8 columns of 10 rows, by 100; U_T = 12 columns.
  EXPECT_EQ(m.truth_pixels, 120);
  EXPECT_NEAR(m.truth_change, 100.0 * 80 / 120, 1e-12);
  EXPECT_NEAR(m.reenacted_change, m.truth_change, 1e-12);
  EXPECT_NEAR(m.flicker(), 0.0, 1e-12);
  EXPECT_NEAR(m.error_change, 0.0, 1e-12);
}

TEST(TemporalFlicker, ATexturePopOnAStillSubjectIsAllFlicker) {
  // The truth stands still; the reenactment's colour jumps from 100 to 160 (another stored
  // frame): every pixel of the subject changes by 60.
  const Frame t = Box(2, 10, 100);
  const FlickerMeasure m = Measure(Box(2, 10, 100), Box(2, 10, 160), t, t);
  EXPECT_NEAR(m.truth_change, 0.0, 1e-12);
  EXPECT_NEAR(m.reenacted_change, 60.0, 1e-12);
  EXPECT_NEAR(m.flicker(), 60.0, 1e-12);
  EXPECT_NEAR(m.error_change, 60.0, 1e-12);
}

TEST(TemporalFlicker, AFrozenReenactmentOfAMovingSubjectHasNegativeFlicker) {
  // The reenactment does not move while the truth does: it changes less (flicker < 0), but
  // its error changes as much as the truth (error_change = truth_change).
  const Frame r = Box(2, 10, 100);
  const FlickerMeasure m = Measure(r, r, Box(2, 10, 100), Box(6, 14, 100));
  EXPECT_NEAR(m.reenacted_change, 0.0, 1e-12);
  EXPECT_LT(m.flicker(), 0.0);
  EXPECT_NEAR(m.error_change, m.truth_change, 1e-12);
}

TEST(TemporalFlicker, PixelsOutsideTheTrueSubjectCountAgainstTheSameArea) {
  // An extra limb (8 columns of 200) appears in the reenactment outside the true silhouette:
  // its change counts in full, divided by the true subject's area (8 columns).
  const Frame t = Box(2, 10, 100);
  Frame rb = Box(2, 10, 100);
  for (int y = 0; y < 10; ++y)
    for (int x = 12; x < 20; ++x) {
      rb.mask.at(x, y) = 255;
      for (int c = 0; c < 3; ++c) rb.color.at(x, y, c) = 200;
    }
  const FlickerMeasure m = Measure(t, rb, t, t);
  EXPECT_EQ(m.truth_pixels, 80);
  EXPECT_NEAR(m.reenacted_change, 200.0, 1e-12);
  EXPECT_NEAR(m.flicker(), 200.0, 1e-12);
}

TEST(TemporalFlicker, EmptySilhouettesGiveZeroAndSizesMustAgree) {
  const Frame empty = Box(0, 0, 0);
  const FlickerMeasure m = Measure(empty, empty, empty, empty);
  EXPECT_EQ(m.reenacted_change, 0.0);
  EXPECT_EQ(m.truth_change, 0.0);
  EXPECT_EQ(m.error_change, 0.0);
  // No true subject: the rendered union normalises.
  const FlickerMeasure only_rendered = Measure(empty, Box(0, 5, 90), empty, empty);
  EXPECT_NEAR(only_rendered.reenacted_change, 90.0, 1e-12);
  EXPECT_THROW(Measure(empty, Box(0, 5, 90, 21, 10), empty, empty), CheckError);
}

}  // namespace
}  // namespace reenact::eval
