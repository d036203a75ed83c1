// The depth picture with two skeletons: grey levels from the frame's depth range, each
// skeleton's bones in its colour where the camera projects them, missing joints not drawn.
#include "tests/eval/skeleton_overlay.h"

#include <gtest/gtest.h>

namespace reenact::eval {
namespace {

PinholeCamera Camera() { return PinholeCamera{80, 60, 70, 70, 40, 30, {}}; }

// A skeleton whose neck and waist lie at the given pixels at depth 2 m (the rest missing).
Skeleton Trunk(double u_neck, double v_neck, double u_waist, double v_waist) {
  const PinholeCamera c = Camera();
  Skeleton s;
  s.Set(Joint::kNeck, c.Unproject({u_neck, v_neck}, 2.0));
  s.Set(Joint::kWaist, c.Unproject({u_waist, v_waist}, 2.0));
  s.Set(Joint::kTorso, c.Unproject({(u_neck + u_waist) / 2, (v_neck + v_waist) / 2}, 2.0));
  return s;
}

std::array<uint8_t, 3> Pixel(const ImageRgb8& image, int x, int y) {
  return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}

TEST(SkeletonOverlay, GreyFromTheFramesDepthRangeAndBonesInTheirColours) {
  ImageDepthMm depth(80, 60, 1, 0);
  depth.at(5, 5) = 2000;   // nearest: 255
  depth.at(6, 5) = 3000;   // farthest: 80
  depth.at(7, 5) = 2500;   // half way
  const ImageRgb8 plain = SkeletonOverlay(depth, Camera(), std::nullopt, std::nullopt,
                                          SkeletonOverlayOptions{.scale = 1, .thickness = 1});
  ASSERT_EQ(plain.width, 80);
  EXPECT_EQ(Pixel(plain, 5, 5), (std::array<uint8_t, 3>{255, 255, 255}));
  EXPECT_EQ(Pixel(plain, 6, 5), (std::array<uint8_t, 3>{80, 80, 80}));
  EXPECT_EQ(Pixel(plain, 7, 5)[0], 168);  // 255 - 175 / 2, rounded
  EXPECT_EQ(Pixel(plain, 0, 0), (std::array<uint8_t, 3>{0, 0, 0}));

  // Reference trunk vertical at u = 20 from v = 10 to 50; the estimate's at u = 60; scaled 2x.
  const ImageRgb8 both = SkeletonOverlay(depth, Camera(), Trunk(20, 10, 20, 50),
                                         Trunk(60, 10, 60, 50));
  ASSERT_EQ(both.width, 160);
  ASSERT_EQ(both.height, 120);
  const auto reference = Pixel(both, 2 * 20, 2 * 30), estimate = Pixel(both, 2 * 60, 2 * 30);
  EXPECT_GT(reference[1], 150);
  EXPECT_LT(reference[0], 50);
  EXPECT_GT(estimate[0], 180);
  EXPECT_LT(estimate[1], 80);
  EXPECT_EQ(Pixel(both, 2 * 40, 2 * 30), (std::array<uint8_t, 3>{0, 0, 0}));  // between
}

TEST(SkeletonOverlay, JointsBehindTheCameraAreNotDrawn) {
  const ImageDepthMm depth(80, 60, 1, 0);
  Skeleton behind = Trunk(20, 10, 20, 50);
  for (auto& p : behind.position) p.z() = -p.z();
  const ImageRgb8 picture = SkeletonOverlay(depth, Camera(), behind, std::nullopt);
  for (uint8_t v : picture.data) ASSERT_EQ(v, 0);
}

}  // namespace
}  // namespace reenact::eval
