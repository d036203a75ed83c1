#include <gtest/gtest.h>

#include <cmath>

#include "tests/unit/common/test_skeletons.h"
#include "viewer-client/play/reenactment.h"

namespace reenact::viewer {
namespace {

// A subject standing still 3 m in front of a static sensor (world = sensor frame) for 9
// frames at 30 fps; frame 4's skeleton is thrown 0.5 m sideways and flagged by the capture.
// With jitter_m, every other frame's skeleton is recorded jitter_m to the right and the rest
// jitter_m to the left (a tracker's frame-to-frame noise).
Reenactment StillClip(const ReenactmentOptions& options, double jitter_m = 0) {
  proto::ClipManifest manifest;
  manifest.flagged_skeleton_frames = {4};
  manifest.color_camera = PinholeCamera::KinectLike();
  manifest.depth_camera = manifest.color_camera;
  manifest.radius_ratio = DefaultRadiusRatios();
  std::vector<proto::ClipFrame> frames;
  for (int n = 0; n < 9; ++n) {
    proto::ClipFrame f;
    f.timestamp_s = n / 30.0;
    f.skeleton_in_world = testing::StandingPerson(3.0, 0.0, true);
    for (Eigen::Vector3d& p : f.skeleton_in_world.position)
      p.x() += n == 4 ? 0.5 : (n % 2 ? jitter_m : -jitter_m);
    f.color = ImageRgb8(4, 4, 3, 100);
    f.depth = ImageDepthMm(4, 4, 1, 3000);
    f.mask = ImageGray8(4, 4, 1, 255);
    frames.push_back(f);
  }
  manifest.frame_count = static_cast<int64_t>(frames.size());
  return Reenactment(manifest, std::move(frames), options);
}

double HeadX(const ReenactedFrame& f) {
  for (size_t i = 0; i < f.cylinder_parts.size(); ++i)
    if (f.cylinder_parts[i] == BodyPart::kHead) return f.draw.cylinders[i].a.x();
  return NAN;
}

TEST(ReenactmentSteady, OffByDefaultPosesTheStoredSkeleton) {
  const Reenactment r = StillClip({});
  EXPECT_FALSE(r.options().steady_motion);
  const ReenactedFrame f = r.Build(4, PinholeCamera::KinectLike(), Eigen::Isometry3d::Identity(),
                                   [](int n) { return n; });
  const double still = testing::StandingPerson(3.0, 0.0, true)[Joint::kHead].x();
  EXPECT_NEAR(HeadX(f), still + 0.5, 1e-12);
}

TEST(ReenactmentSteady, SteadyMotionPosesTheFlaggedFrameFromItsNeighbours) {
  ReenactmentOptions options;
  options.steady_motion = true;
  const Reenactment r = StillClip(options);
  const double still = testing::StandingPerson(3.0, 0.0, true)[Joint::kHead].x();
  for (int k = 0; k < r.frame_count(); ++k) {
    const ReenactedFrame f = r.Build(k, PinholeCamera::KinectLike(), Eigen::Isometry3d::Identity(),
                                     [](int n) { return n; });
    // The flagged skeleton is dropped and interpolated from two identical neighbours, so the
    // steady track stands still and the filter passes it unchanged.
    EXPECT_NEAR(HeadX(f), still, 1e-12) << k;
    EXPECT_NE(f.texture_frame, 4) << k;  // never textured from the flagged frame
  }
  // BuildPosed with the steady skeleton is what Build does with the option on.
  const ReenactedFrame posed =
      r.BuildPosed(4, r.SteadySkeletonInWorld(4), PinholeCamera::KinectLike(),
                   Eigen::Isometry3d::Identity(), [](int n) { return n; }, r.options().texturing);
  EXPECT_NEAR(HeadX(posed), still, 1e-12);
}

TEST(ReenactmentSteady, SteadyMotionTexturesFromTheStoredFramesOnTheSteadyTrack) {
  // The pose shown and the frames it is textured from must agree: with steady_motion every
  // unflagged frame's own skeleton is its steady one, wherever the clip uses it.
  constexpr double kJitter = 0.01;
  const Reenactment raw = StillClip({}, kJitter);
  ReenactmentOptions options;
  options.steady_motion = true;
  const Reenactment steady = StillClip(options, kJitter);
  const double still = testing::StandingPerson(3.0, 0.0, true)[Joint::kHead].x();
  for (int n = 0; n < steady.frame_count(); ++n) {
    const Skeleton& stored = steady.frame(n).skeleton_in_world;
    if (n == 4) {  // flagged: kept as recorded, and never a texture
      EXPECT_EQ(stored[Joint::kHead], raw.frame(4).skeleton_in_world[Joint::kHead]);
      continue;
    }
    for (int j = 0; j < kJointCount; ++j)
      EXPECT_EQ(stored.position[j], steady.SteadySkeletonInWorld(n).position[j]) << n << " " << j;
    // Off, the frame keeps its recorded skeleton, jitter and all.
    EXPECT_NEAR(std::abs(raw.frame(n).skeleton_in_world[Joint::kHead].x() - still), kJitter, 1e-12);
    // The steady track smooths the alternation, so the stored frame moves nearer the truth.
    EXPECT_LT(std::abs(stored[Joint::kHead].x() - still), kJitter) << n;
  }
  for (int k = 0; k < steady.frame_count(); ++k)
    EXPECT_NE(steady
                  .Build(k, PinholeCamera::KinectLike(), Eigen::Isometry3d::Identity(),
                         [](int n) { return n; })
                  .texture_frame,
              4)
        << k;
}

}  // namespace
}  // namespace reenact::viewer
