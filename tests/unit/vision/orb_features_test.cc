#include <gtest/gtest.h>

#include <random>

#include "vision/features/orb_features.h"
#include "common/error/check.h"

namespace reenact::vision {
namespace {

PinholeCamera Camera() { return PinholeCamera::KinectLike(); }

// Random 8x8-pixel blocks of grey: corners everywhere.
cv::Mat Blocks(uint64_t seed) {
  std::mt19937_64 rng(seed);
  cv::Mat g(480, 640, CV_8UC1);
  for (int by = 0; by < 480; by += 8)
    for (int bx = 0; bx < 640; bx += 8) g(cv::Rect(bx, by, 8, 8)).setTo(rng() % 256);
  return g;
}

ImageDepthMm FlatDepth(uint16_t mm) { return ImageDepthMm(640, 480, 1, mm); }

TEST(SlamFeatures, TexturedImageGivesSpreadKeypointsWithDepth) {
  OrbFeatureOptions o;
  const FrameFeatures f =
      ExtractOrbFeatures(Blocks(1), FlatDepth(2000), 0.001, nullptr, Camera(), o);
  ASSERT_EQ(static_cast<int>(f.size()), o.num_features);
  EXPECT_EQ(f.descriptors.rows, o.num_features);
  EXPECT_EQ(f.CountWithDepth(), o.num_features);
  // Spread: every quarter of the image has at least a sixth of the keypoints.
  int quarter[4] = {0, 0, 0, 0};
  for (const auto& kp : f.keypoints) ++quarter[(kp.pt.x >= 320) + 2 * (kp.pt.y >= 240)];
  for (int q : quarter) EXPECT_GT(q, o.num_features / 6);
  for (size_t i = 0; i < f.size(); ++i) {
    EXPECT_DOUBLE_EQ(f.observations[i].depth_m, 2.0);
    EXPECT_NEAR(f.points_in_camera[i].z(), 2.0, 1e-12);
    const Eigen::Vector2d n = Camera().Undistort({f.keypoints[i].pt.x, f.keypoints[i].pt.y});
    EXPECT_LT((f.observations[i].normalized - n).norm(), 1e-12);
    EXPECT_EQ(f.observations[i].octave, f.keypoints[i].octave);
  }
}

TEST(SlamFeatures, TexturelessImageGivesNone) {
  const cv::Mat grey(480, 640, CV_8UC1, cv::Scalar(128));
  const FrameFeatures f = ExtractOrbFeatures(grey, FlatDepth(1500), 0.001, nullptr, Camera(), {});
  EXPECT_EQ(f.size(), 0u);
  EXPECT_EQ(f.descriptors.rows, 0);
  EXPECT_EQ(f.CountWithDepth(), 0);
}

TEST(SlamFeatures, PersonMaskGrownByTheDilationExcludesKeypoints) {
  ImageGray8 mask(640, 480, 1, 0);
  const cv::Rect person(250, 100, 140, 300);
  for (int y = person.y; y < person.y + person.height; ++y)
    for (int x = person.x; x < person.x + person.width; ++x) mask.at(x, y) = 255;
  OrbFeatureOptions o;
  o.mask_dilation_px = 15;
  const FrameFeatures f = ExtractOrbFeatures(Blocks(2), FlatDepth(2000), 0.001, &mask, Camera(), o);
  ASSERT_GT(f.size(), 300u);
  // The keypoints' pixel positions carry OpenCV's level rounding (up to a pixel or two), so
  // the check leaves 3 pixels of the 15.
  const cv::Rect grown(person.x - 12, person.y - 12, person.width + 24, person.height + 24);
  for (const auto& kp : f.keypoints) EXPECT_FALSE(grown.contains(kp.pt)) << kp.pt;
  // Without the mask the same region has keypoints (so the check above can fail).
  const FrameFeatures all =
      ExtractOrbFeatures(Blocks(2), FlatDepth(2000), 0.001, nullptr, Camera(), o);
  int inside = 0;
  for (const auto& kp : all.keypoints) inside += person.contains(kp.pt);
  EXPECT_GT(inside, 50);
}

TEST(SlamFeatures, DepthOnEdgesHolesAndOutOfRangeIsNotUsed) {
  ImageDepthMm depth(640, 480, 1, 0);
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 640; ++x) depth.at(x, y) = x < 320 ? 1000 : (x < 480 ? 2000 : 9000);
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 320; ++x) depth.at(x, y) = 0;  // a hole
  OrbFeatureOptions o;
  o.max_depth_m = 6;
  const FrameFeatures f = ExtractOrbFeatures(Blocks(3), depth, 0.001, nullptr, Camera(), o);
  int far_from_edge = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    const int x = static_cast<int>(std::lround(f.keypoints[i].pt.x));
    const int y = static_cast<int>(std::lround(f.keypoints[i].pt.y));
    const double d = f.observations[i].depth_m;
    if (x >= 480 || (x < 320 && y < 100)) {
      EXPECT_EQ(d, 0) << "beyond max_depth_m or in the hole at " << x << "," << y;
    } else if (x == 319 || x == 320 || x == 479) {  // their 3x3 windows straddle an edge
      EXPECT_EQ(d, 0) << "on the depth edge at " << x;
    } else if (x < 320) {
      EXPECT_DOUBLE_EQ(d, 1.0);
      ++far_from_edge;
    } else {
      EXPECT_DOUBLE_EQ(d, 2.0);
      ++far_from_edge;
    }
  }
  EXPECT_GT(far_from_edge, 200);
}

// Dark 10x10 squares on a light ground, their corners at a known fraction of a pixel
// (x + 0.37, y + 0.61), each pixel the exact area fraction it covers (pixel centres at
// integers). Returns the image and fills the true corner positions.
cv::Mat SquaresAtSubpixelOffsets(std::vector<cv::Point2d>* corners) {
  cv::Mat g(480, 640, CV_8UC1);
  std::vector<cv::Rect2d> boxes;
  for (int j = 0; j < 14; ++j)
    for (int i = 0; i < 20; ++i) {
      const cv::Rect2d box(20 + 30 * i + 0.37, 20 + 32 * j + 0.61, 10, 10);
      boxes.push_back(box);
      for (double dx : {0.0, 10.0})
        for (double dy : {0.0, 10.0}) corners->push_back({box.x + dx, box.y + dy});
    }
  const auto overlap = [](double lo, double hi, double p) {
    return std::max(0.0, std::min(hi, p + 0.5) - std::max(lo, p - 0.5));
  };
  for (int y = 0; y < g.rows; ++y)
    for (int x = 0; x < g.cols; ++x) {
      double dark = 0;
      for (const cv::Rect2d& b : boxes)
        dark += overlap(b.x, b.x + b.width, x) * overlap(b.y, b.y + b.height, y);
      g.at<uint8_t>(y, x) = static_cast<uint8_t>(std::lround(200 - 160 * dark));
    }
  return g;
}

TEST(SlamFeatures, SubpixelKeypointsLandOnTheTrueCorners) {
  std::vector<cv::Point2d> corners;
  const cv::Mat image = SquaresAtSubpixelOffsets(&corners);
  // Mean distance of level-0 keypoints to the nearest true corner (those within 2 px).
  const auto mean_error = [&](bool subpixel) {
    OrbFeatureOptions o;
    o.subpixel = subpixel;
    const FrameFeatures f = ExtractOrbFeatures(image, FlatDepth(2000), 0.001, nullptr, Camera(), o);
    double sum = 0;
    int n = 0;
    for (const cv::KeyPoint& kp : f.keypoints) {
      if (kp.octave != 0) continue;
      double best = INFINITY;
      for (const cv::Point2d& c : corners)
        best = std::min(best, std::hypot(kp.pt.x - c.x, kp.pt.y - c.y));
      if (best < 2) sum += best, ++n;
    }
    EXPECT_GT(n, 200) << "subpixel " << subpixel;
    return n ? sum / n : INFINITY;
  };
  const double integer = mean_error(false), refined = mean_error(true);
  // Whole-pixel keypoints cannot come nearer than the offset (0.37, 0.61) rounds to: at
  // least 0.39 px from every true corner (FAST's own keypoints sit further inside the
  // squares). Refined ones land on the corner to a fraction of that.
  EXPECT_GT(integer, 0.38);
  EXPECT_LT(refined, 0.25);
}

TEST(SlamFeatures, DescriptorDistanceCountsDifferingBits) {
  uint8_t a[32] = {}, b[32] = {};
  EXPECT_EQ(DescriptorDistance(a, b), 0);
  b[0] = 0xFF;
  b[31] = 0x01;
  b[17] = 0x0F;
  EXPECT_EQ(DescriptorDistance(a, b), 13);
  std::fill(std::begin(b), std::end(b), 0xFF);
  EXPECT_EQ(DescriptorDistance(a, b), 256);
}

TEST(SlamFeatures, BadInputAndOptionsAreBugs) {
  OrbFeatureOptions o;
  o.num_features = 0;
  EXPECT_THROW(o.Check(), CheckError);
  o = {};
  o.min_depth_m = 2;
  o.max_depth_m = 1;
  EXPECT_THROW(o.Check(), CheckError);
  EXPECT_THROW(
      ExtractOrbFeatures(Blocks(1), ImageDepthMm(320, 240, 1, 0), 0.001, nullptr, Camera(), {}),
      CheckError);
}

}  // namespace
}  // namespace reenact::vision
