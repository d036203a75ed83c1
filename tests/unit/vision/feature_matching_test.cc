#include "vision/features/feature_matching.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace reenact::vision {
namespace {

cv::Mat Blocks(uint64_t seed) {
  std::mt19937_64 rng(seed);
  cv::Mat g(480, 640, CV_8UC1);
  for (int by = 0; by < 480; by += 8)
    for (int bx = 0; bx < 640; bx += 8) g(cv::Rect(bx, by, 8, 8)).setTo(rng() % 256);
  return g;
}

// Features of a textured plane 2 m away and map points made of them (point id = keypoint).
struct Fixture {
  PinholeCamera camera = PinholeCamera::KinectLike();
  FrameFeatures features;
  std::vector<MatchCandidate> candidates;

  Fixture() {
    features =
        ExtractOrbFeatures(Blocks(7), ImageDepthMm(640, 480, 1, 2000), 0.001, nullptr, camera, {});
    for (size_t i = 0; i < features.size(); ++i) {
      MatchCandidate c;
      c.id = static_cast<int>(i);
      c.point_in_world = features.points_in_camera[i];
      c.descriptor = features.Descriptor(i);
      c.predicted_octave = features.keypoints[i].octave;
      candidates.push_back(c);
    }
  }
};

TEST(SlamMatching, GridReturnsExactlyTheKeypointsWithinTheRadius) {
  Fixture fx;
  const KeypointGrid grid(fx.features, 640, 480);
  std::vector<int> found;
  grid.Query(300.5, 200.25, 23, found);
  std::vector<int> expected;
  for (size_t i = 0; i < fx.features.size(); ++i) {
    const double dx = fx.features.keypoints[i].pt.x - 300.5,
                 dy = fx.features.keypoints[i].pt.y - 200.25;
    if (dx * dx + dy * dy <= 23 * 23) expected.push_back(static_cast<int>(i));
  }
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, expected);
  grid.Query(std::nan(""), 0, 10, found);
  EXPECT_TRUE(found.empty());
}

TEST(SlamMatching, ProjectionWithTheTruePoseMatchesEveryPointToItsKeypoint) {
  Fixture fx;
  const KeypointGrid grid(fx.features, 640, 480);
  std::vector<char> in_view;
  const auto matches = MatchByProjection(fx.candidates, fx.features, grid,
                                         Eigen::Isometry3d::Identity(), fx.camera, {}, &in_view);
  ASSERT_GT(matches.size(), 0.9 * fx.features.size());
  for (const auto& m : matches) {
    EXPECT_EQ(m.id, m.keypoint);
    EXPECT_EQ(m.distance, 0);
  }
  for (char v : in_view) EXPECT_TRUE(v);
}

TEST(SlamMatching, ProjectionOutsideTheRadiusFindsNothingAndBehindIsNotInView) {
  Fixture fx;
  const KeypointGrid grid(fx.features, 640, 480);
  // Shift the camera 60 px sideways at 2 m (0.23 m): beyond a 15 px radius at every level.
  Eigen::Isometry3d shifted = Eigen::Isometry3d::Identity();
  shifted.translation().x() = 60.0 * 2 / fx.camera.fx;
  MatchOptions o;
  o.radius_px = 4;
  o.max_distance = 0;  // only identical descriptors: the true keypoints
  const auto matches = MatchByProjection(fx.candidates, fx.features, grid, shifted, fx.camera, o);
  EXPECT_TRUE(matches.empty());
  Eigen::Isometry3d turned = Eigen::Isometry3d::Identity();
  turned.linear() =
      Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitY()).toRotationMatrix();
  std::vector<char> in_view;
  EXPECT_TRUE(
      MatchByProjection(fx.candidates, fx.features, grid, turned, fx.camera, {}, &in_view).empty());
  for (char v : in_view) EXPECT_FALSE(v);
}

TEST(SlamMatching, DescriptorMatchingFindsTheSameKeypointsAndKeepsOnePerKeypoint) {
  Fixture fx;
  const auto matches = MatchByDescriptor(fx.candidates, fx.features, {});
  ASSERT_GT(matches.size(), 0.9 * fx.features.size());
  for (const auto& m : matches) EXPECT_EQ(m.id, m.keypoint);
  // Two identical candidates for each point: the ratio test rejects them all.
  auto doubled = fx.candidates;
  for (auto c : fx.candidates) {
    c.id += 100000;
    doubled.push_back(c);
  }
  EXPECT_TRUE(MatchByDescriptor(doubled, fx.features, {}).empty());
}

// The grid's answer is the brute-force set of keypoints within the radius, whatever the
// radius and position (also near and beyond the image's edges).
TEST(KeypointGrid, QueryEqualsBruteForce) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> ux(0, 639.99f), uy(0, 479.99f);
  FrameFeatures features;
  for (int i = 0; i < 3000; ++i) features.keypoints.emplace_back(ux(rng), uy(rng), 7.f);
  const KeypointGrid grid(features, 640, 480);
  std::uniform_real_distribution<double> qx(-30, 670), qy(-30, 510), qr(0.5, 40);
  std::vector<int> got;
  for (int q = 0; q < 500; ++q) {
    const double x = qx(rng), y = qy(rng), r = qr(rng);
    grid.Query(x, y, r, got);
    std::vector<int> want;
    for (int i = 0; i < 3000; ++i) {
      const double dx = features.keypoints[i].pt.x - x, dy = features.keypoints[i].pt.y - y;
      if (dx * dx + dy * dy <= r * r) want.push_back(i);
    }
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, want) << "query " << q;
  }
  grid.Query(std::nan(""), 10, 5, got);
  EXPECT_TRUE(got.empty());
  grid.Query(10, 10, 0, got);
  EXPECT_TRUE(got.empty());
}

// MatchStats counts what was done: every candidate projected, those in view, and one
// descriptor comparison per keypoint found near an in-view candidate's projection.
TEST(MatchByProjection, StatsCountTheWork) {
  Fixture fx;
  const KeypointGrid grid(fx.features, 640, 480);
  MatchOptions o;
  o.radius_px = 8;
  std::vector<MatchCandidate> candidates = fx.candidates;
  for (MatchCandidate& c : candidates) c.predicted_octave = -1;  // any level, radius as given
  MatchStats stats;
  std::vector<char> in_view;
  MatchByProjection(candidates, fx.features, grid, Eigen::Isometry3d::Identity(), fx.camera, o,
                    &in_view, &stats);
  EXPECT_EQ(stats.projected, static_cast<int64_t>(candidates.size()));
  int64_t expected_in_view = 0, expected_comparisons = 0;
  std::vector<int> near;
  for (size_t c = 0; c < candidates.size(); ++c) {
    if (!in_view[c]) continue;
    ++expected_in_view;
    const auto px = fx.camera.Project(candidates[c].point_in_world);
    grid.Query(px->x(), px->y(), o.radius_px, near);
    expected_comparisons += static_cast<int64_t>(near.size());
  }
  EXPECT_EQ(stats.in_view, expected_in_view);
  EXPECT_GT(stats.in_view, 0);
  EXPECT_EQ(stats.comparisons, expected_comparisons);
  // Added to, not reset.
  MatchByProjection(candidates, fx.features, grid, Eigen::Isometry3d::Identity(), fx.camera, o,
                    nullptr, &stats);
  EXPECT_EQ(stats.projected, 2 * static_cast<int64_t>(candidates.size()));
  EXPECT_EQ(stats.comparisons, 2 * expected_comparisons);
}

}  // namespace
}  // namespace reenact::vision
