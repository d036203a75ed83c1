// SLAM on real data: the first 60 frames of TUM RGB-D fr1_rpy (../shared/data), a hand-held
// Kinect turning about all three axes over a desk (fast rotations, motion blur).
#include <gtest/gtest.h>

#include "capture-client/slam/rgbd_slam.h"
#include "capture-client/slam/rolling_shutter.h"
#include "common/align/trajectory_error.h"
#include "tests/unit/capture-client/slam_test_support.h"

namespace reenact::capture::slam {
namespace {

TEST(SlamTum, FreiburgRpyIsTrackedWithinAFractionOfItsMotion) {
  const test_input::Sequence s = test_input::LoadTum(test_input::TumRpyDir(), 60);
  if (s.frames.empty()) GTEST_SKIP() << "no TUM data at " << test_input::TumRpyDir();
  SlamOptions o;
  o.readout_ratio = kKinectV1ReadoutRatio;  // the Kinect's rolling shutter
  RgbdSlam slam(s.camera, s.depth_scale_m, o);
  std::vector<Eigen::Isometry3d> truth, estimate;
  for (const auto& f : s.frames) {
    const auto r = slam.Track(f.timestamp_s, f.color, f.depth);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_TRUE(r->has_pose()) << r->frame_index << " " << SlamStatusName(r->status);
    if (r->has_pose() && f.truth_world_from_sensor) {
      truth.push_back(*f.truth_world_from_sensor);
      estimate.push_back(*r->world_from_sensor);
    }
  }
  ASSERT_EQ(truth.size(), s.frames.size());
  // The bound comes from the trajectory itself: the RMS distance of the true positions from
  // their mean is what an estimate that got the turning right but left the sensor at one
  // place would score. Tracking must explain most of that motion: at most half of it may
  // remain as error.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& t : truth) mean += t.translation() / truth.size();
  double spread = 0;
  for (const auto& t : truth) spread += (t.translation() - mean).squaredNorm() / truth.size();
  spread = std::sqrt(spread);
  ASSERT_GT(spread, 0.02);  // the sensor does move (about 4 cm)
  const auto ate = AbsoluteTrajectoryError(truth, estimate);
  ASSERT_TRUE(ate.ok());
  EXPECT_LT(ate.ate_rmse_m, spread / 2) << "spread " << spread << " m";
  EXPECT_GT(slam.ExportClipMap().points.size(), 200u);
}

}  // namespace
}  // namespace reenact::capture::slam
