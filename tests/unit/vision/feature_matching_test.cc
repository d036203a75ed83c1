#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "vision/features/feature_matching.h"

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

}  // namespace
}  // namespace reenact::vision
