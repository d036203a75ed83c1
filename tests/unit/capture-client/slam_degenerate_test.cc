// SLAM on degenerate and bad input: a defined status (or a clear Error), never a crash.
#include <gtest/gtest.h>

#include <random>

#include "capture-client/slam/rgbd_slam.h"
#include "common/error/check.h"
#include "tests/unit/capture-client/slam_test_support.h"

namespace reenact::capture::slam {
namespace {

using test_input::Sequence;

const Sequence& Walk() { return test_input::WalkHandheld(60, 2); }

SlamOptions NoFallback() {
  SlamOptions o;
  o.odometry_fallback = false;
  return o;
}

ImageRgb8 Uniform(int w, int h, uint8_t v) { return ImageRgb8(w, h, 3, v); }

TEST(SlamDegenerate, TexturelessFramesNeverFoundAMap) {
  RgbdSlam slam(Walk().camera, 0.001);
  for (int i = 0; i < 5; ++i) {
    const auto r = slam.Track(i / 30.0, Uniform(640, 480, 128), ImageDepthMm(640, 480, 1, 1500));
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->status, SlamStatus::kLost);
    EXPECT_EQ(r->lost_reason, SlamLostReason::kNotInitialised);
    EXPECT_FALSE(r->has_pose());
    EXPECT_EQ(r->features, 0);
  }
  EXPECT_FALSE(slam.initialised());
  EXPECT_FALSE(slam.lost());  // nothing to be lost from
  EXPECT_FALSE(slam.PredictedWorldFromSensor());
  EXPECT_TRUE(slam.ExportClipMap().points.empty());
}

TEST(SlamDegenerate, AllZeroDepthNeverFoundsAMap) {
  const auto& f = Walk().frames[0];
  RgbdSlam slam(Walk().camera, 0.001);
  const auto r = slam.Track(0, f.color, ImageDepthMm(640, 480, 1, 0), &f.mask);
  ASSERT_TRUE(r.ok());
  EXPECT_GT(r->features, 100);  // plenty of texture, but nothing to lift it to 3D
  EXPECT_EQ(r->status, SlamStatus::kLost);
  EXPECT_EQ(r->lost_reason, SlamLostReason::kNotInitialised);
  EXPECT_TRUE(slam.map().keyframes().empty());
}

TEST(SlamDegenerate, ZeroDepthAfterTheStartIsTrackedByReprojectionAlone) {
  const Sequence& s = Walk();
  RgbdSlam slam(s.camera, 0.001);
  for (int i = 0; i < 3; ++i)
    ASSERT_TRUE(
        slam.Track(s.frames[i].timestamp_s, s.frames[i].color, s.frames[i].depth, &s.frames[i].mask)
            .ok());
  const auto& f = s.frames[3];
  const auto r = slam.Track(f.timestamp_s, f.color, ImageDepthMm(640, 480, 1, 0), &f.mask);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->status, SlamStatus::kTracked);
  ASSERT_TRUE(r->has_pose());
  const Eigen::Isometry3d truth =
      s.frames[0].truth_world_from_sensor->inverse() * *f.truth_world_from_sensor;
  EXPECT_LT((truth.translation() - r->world_from_sensor->translation()).norm(), 0.03);
}

TEST(SlamDegenerate, TexturelessFrameAfterTheStartIsLostThenRelocalised) {
  const Sequence& s = Walk();
  RgbdSlam slam(s.camera, 0.001, NoFallback());
  for (int i = 0; i < 5; ++i)
    ASSERT_TRUE(
        slam.Track(s.frames[i].timestamp_s, s.frames[i].color, s.frames[i].depth, &s.frames[i].mask)
            .ok());
  const auto lost = slam.Track(0.2, Uniform(640, 480, 90), ImageDepthMm(640, 480, 1, 1200));
  ASSERT_TRUE(lost.ok());
  EXPECT_EQ(lost->status, SlamStatus::kLost);
  EXPECT_EQ(lost->lost_reason, SlamLostReason::kTooFewFeatures);
  EXPECT_FALSE(lost->has_pose());
  EXPECT_TRUE(slam.lost());
  EXPECT_FALSE(slam.PredictedWorldFromSensor());  // no pose to carry on
  const auto& f = s.frames[6];
  const auto back = slam.Track(f.timestamp_s, f.color, f.depth, &f.mask);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->status, SlamStatus::kRelocalised);
  EXPECT_FALSE(slam.lost());
  // Relocalised: the relocalised pose, without a motion (none is known across the gap).
  ASSERT_TRUE(slam.PredictedWorldFromSensor() && back->world_from_sensor);
  EXPECT_LT((slam.PredictedWorldFromSensor()->matrix() - back->world_from_sensor->matrix()).norm(),
            1e-12);
}

TEST(SlamDegenerate, TexturelessFrameWithTheFallbackOnIsDefined) {
  const Sequence& s = Walk();
  RgbdSlam slam(s.camera, 0.001);
  for (int i = 0; i < 3; ++i)
    ASSERT_TRUE(
        slam.Track(s.frames[i].timestamp_s, s.frames[i].color, s.frames[i].depth, &s.frames[i].mask)
            .ok());
  for (uint16_t depth : {uint16_t{1200}, uint16_t{0}}) {
    const auto r = slam.Track(0.2, Uniform(640, 480, 90), ImageDepthMm(640, 480, 1, depth));
    ASSERT_TRUE(r.ok());
    if (r->has_pose()) {
      EXPECT_EQ(r->status, SlamStatus::kOdometryFallback);
      EXPECT_TRUE(r->world_from_sensor->matrix().allFinite());
    } else {
      EXPECT_EQ(r->status, SlamStatus::kLost);
      EXPECT_NE(r->lost_reason, SlamLostReason::kNone);
    }
  }
}

TEST(SlamDegenerate, UnrelatedTextureGivesTooFewInliers) {
  const Sequence& s = Walk();
  RgbdSlam slam(s.camera, 0.001, NoFallback());
  for (int i = 0; i < 5; ++i)
    ASSERT_TRUE(
        slam.Track(s.frames[i].timestamp_s, s.frames[i].color, s.frames[i].depth, &s.frames[i].mask)
            .ok());
  std::mt19937_64 rng(3);
  ImageRgb8 noise(640, 480, 3);
  for (int by = 0; by < 480; by += 6)
    for (int bx = 0; bx < 640; bx += 6) {
      const uint8_t v = static_cast<uint8_t>(rng());
      for (int y = by; y < by + 6; ++y)
        for (int x = bx; x < bx + 6; ++x)
          for (int c = 0; c < 3; ++c) noise.at(x, y, c) = v;
    }
  const auto r = slam.Track(0.2, noise, ImageDepthMm(640, 480, 1, 1500));
  ASSERT_TRUE(r.ok());
  EXPECT_GT(r->features, 500);
  EXPECT_EQ(r->status, SlamStatus::kLost);
  EXPECT_EQ(r->lost_reason, SlamLostReason::kTooFewInliers);
  EXPECT_LT(r->inliers, NoFallback().min_tracking_inliers);
}

// Bad frames: an Error naming the problem, and the tracker's state untouched.
void ExpectRefused(const Expected<SlamFrameResult>& r, const RgbdSlam& slam,
                   const std::string& mentions) {
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, "invalid_argument");
  EXPECT_NE(r.error().message.find(mentions), std::string::npos) << r.error().message;
  EXPECT_EQ(slam.frames_seen(), 0);
}

TEST(SlamDegenerate, ColourOfTheWrongSizeIsRefused) {
  RgbdSlam slam(Walk().camera, 0.001);
  ExpectRefused(slam.Track(0, Uniform(320, 240, 1), ImageDepthMm(640, 480, 1, 1000)), slam,
                "colour is 320x240");
}

TEST(SlamDegenerate, ColourWithOneChannelIsRefused) {
  RgbdSlam slam(Walk().camera, 0.001);
  ExpectRefused(slam.Track(0, ImageRgb8(640, 480, 1), ImageDepthMm(640, 480, 1, 1000)), slam,
                "1 channels");
}

TEST(SlamDegenerate, DepthOfAnotherSizeThanColourIsRefused) {
  RgbdSlam slam(Walk().camera, 0.001);
  ExpectRefused(slam.Track(0, Uniform(640, 480, 1), ImageDepthMm(320, 240, 1, 1000)), slam,
                "depth is 320x240");
}

TEST(SlamDegenerate, MaskOfTheWrongSizeIsRefused) {
  RgbdSlam slam(Walk().camera, 0.001);
  const ImageGray8 mask(100, 100, 1, 0);
  ExpectRefused(slam.Track(0, Uniform(640, 480, 1), ImageDepthMm(640, 480, 1, 1000), &mask), slam,
                "person mask is 100x100");
}

TEST(SlamDegenerate, NonFiniteTimestampIsRefused) {
  RgbdSlam slam(Walk().camera, 0.001);
  ExpectRefused(slam.Track(std::nan(""), Uniform(640, 480, 1), ImageDepthMm(640, 480, 1, 1000)),
                slam, "timestamp");
}

TEST(SlamDegenerate, StatusAndReasonNames) {
  EXPECT_EQ(SlamStatusName(SlamStatus::kTracked), "tracked");
  EXPECT_EQ(SlamStatusName(SlamStatus::kOdometryFallback), "odometry_fallback");
  EXPECT_EQ(SlamStatusName(SlamStatus::kRelocalised), "relocalised");
  EXPECT_EQ(SlamStatusName(SlamStatus::kInitialised), "initialised");
  EXPECT_EQ(SlamStatusName(SlamStatus::kLost), "lost");
  EXPECT_EQ(SlamLostReasonName(SlamLostReason::kTooFewInliers), "too_few_inliers");
  EXPECT_EQ(SlamLostReasonName(SlamLostReason::kNotInitialised), "not_initialised");
}

TEST(SlamDegenerate, OptionsOutOfRangeAndBadCamerasAreBugs) {
  auto refused = [](auto change) {
    SlamOptions o;
    change(o);
    EXPECT_THROW(o.Check(), CheckError);
  };
  refused([](SlamOptions& o) { o.min_tracking_inliers = 2; });
  refused([](SlamOptions& o) { o.match_ratio = 0; });
  refused([](SlamOptions& o) { o.readout_ratio = 1.2; });
  refused([](SlamOptions& o) { o.search_radius_px = -1; });
  refused([](SlamOptions& o) { o.keyframe_min_tracked_ratio = 2; });
  refused([](SlamOptions& o) { o.bundle_window_keyframes = 0; });
  refused([](SlamOptions& o) { o.features.num_features = 0; });
  refused([](SlamOptions& o) { o.initial_world_from_sensor.linear() *= 2; });
  EXPECT_NO_THROW(SlamOptions{}.Check());
  PinholeCamera bad = Walk().camera;
  bad.fx = 0;
  EXPECT_THROW(RgbdSlam(bad, 0.001), CheckError);
  EXPECT_THROW(RgbdSlam(Walk().camera, 0), CheckError);
}

}  // namespace
}  // namespace reenact::capture::slam
