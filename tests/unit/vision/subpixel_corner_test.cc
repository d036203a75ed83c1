// Sub-pixel corners against corners drawn at known sub-pixel positions (area-sampled, so the
// true corner is known by construction), and against cv::cornerSubPix.
#include "vision/features/subpixel_corner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

#include "common/error/check.h"

namespace reenact::vision {
namespace {

// A bright quadrant x >= cx, y >= cy (pixel centres at integers) on a dark background,
// each pixel the exact area fraction covered (pixel [x - 1/2, x + 1/2]).
cv::Mat Quadrant(double cx, double cy, int size = 64, int dark = 40, int bright = 220) {
  cv::Mat img(size, size, CV_8UC1);
  auto cover = [](double lo, double edge) {
    return std::clamp(lo + 1 - edge, 0.0, 1.0);  // share of [lo, lo+1] at or above edge
  };
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double f = cover(x - 0.5, cx) * cover(y - 0.5, cy);
      img.at<uint8_t>(y, x) = static_cast<uint8_t>(std::lround(dark + f * (bright - dark)));
    }
  return img;
}

// The estimate is cv::cornerSubPix's (to float rounding), from a pixel off, and closer to the
// true corner than the whole pixel nearest to it (the estimator itself is biased towards the
// bright quadrant by up to ~0.3 px on a hard, area-sampled corner with a small window).
TEST(SubpixelCorner, MatchesCornerSubPixOnAreaSampledCorners) {
  const SubpixelCornerRefiner refiner;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int trial = 0; trial < 20; ++trial) {
    const double cx = 32 + u(rng), cy = 31 + u(rng);
    const cv::Mat img = Quadrant(cx, cy);
    const Eigen::Vector2f start(static_cast<float>(cx + 1), static_cast<float>(cy - 1));
    for (int h : {2, 3, 5}) {
      SCOPED_TRACE("trial " + std::to_string(trial) + " h " + std::to_string(h));
      const auto q = refiner.Refine(img, start, h);
      ASSERT_TRUE(q.has_value());
      std::vector<cv::Point2f> p{{start.x(), start.y()}};
      cv::cornerSubPix(img, p, {h, h}, {-1, -1},
                       cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 10, 0.01));
      EXPECT_NEAR(q->x(), p[0].x, 0.005);
      EXPECT_NEAR(q->y(), p[0].y, 0.005);
      EXPECT_LT(std::hypot(q->x() - cx, q->y() - cy), 0.35);
    }
  }
}

TEST(SubpixelCorner, AgreesWithOpenCvCornerSubPix) {
  const SubpixelCornerRefiner refiner;
  cv::Mat img = Quadrant(30.3, 33.7);
  cv::GaussianBlur(img, img, {5, 5}, 1.0);
  for (int h : {2, 4}) {
    std::vector<cv::Point2f> p{{31, 33}};
    cv::cornerSubPix(img, p, {h, h}, {-1, -1},
                     cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 10, 0.01));
    const auto q = refiner.Refine(img, {31, 33}, h);
    ASSERT_TRUE(q.has_value());
    EXPECT_NEAR(q->x(), p[0].x, 0.02);
    EXPECT_NEAR(q->y(), p[0].y, 0.02);
  }
}

TEST(SubpixelCorner, FlatWindowAndStraightEdgeGiveNothing) {
  const SubpixelCornerRefiner refiner;
  const cv::Mat flat(40, 40, CV_8UC1, cv::Scalar(128));
  EXPECT_FALSE(refiner.Refine(flat, {20, 20}, 3).has_value());
  cv::Mat edge(40, 40, CV_8UC1, cv::Scalar(30));
  edge.colRange(20, 40).setTo(200);  // a vertical edge: no corner along y
  EXPECT_FALSE(refiner.Refine(edge, {20, 20}, 3).has_value());
}

TEST(SubpixelCorner, WindowLeavingTheImageGivesNothing) {
  const SubpixelCornerRefiner refiner;
  const cv::Mat img = Quadrant(3.2, 30.4);
  EXPECT_FALSE(refiner.Refine(img, {3, 30}, 3).has_value());    // needs x from -1
  EXPECT_FALSE(refiner.Refine(img, {62, 30}, 3).has_value());   // beyond the right side
  EXPECT_FALSE(refiner.Refine(img, {NAN, 30}, 3).has_value());  // not a position
  EXPECT_TRUE(refiner.Refine(Quadrant(10.2, 30.4), {10, 30}, 3).has_value());
}

TEST(SubpixelCorner, RejectsBadArguments) {
  const SubpixelCornerRefiner refiner;
  const cv::Mat img = Quadrant(32, 32);
  EXPECT_THROW(refiner.Refine(img, {32, 32}, 0), CheckError);
  cv::Mat color;
  cv::cvtColor(img, color, cv::COLOR_GRAY2BGR);
  EXPECT_THROW(refiner.Refine(color, {32, 32}, 3), CheckError);
  EXPECT_THROW(SubpixelCornerRefiner({.max_iterations = 0}), CheckError);
  EXPECT_THROW(SubpixelCornerRefiner({.epsilon_px = 0}), CheckError);
}

}  // namespace
}  // namespace reenact::vision
