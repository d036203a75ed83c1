#include "viewer-client/play/reenactment.h"

#include <cmath>

#include <gtest/gtest.h>

#include "tests/unit/common/test_skeletons.h"

namespace reenact::viewer {
namespace {

// A clip of a person turning in place in front of a static sensor at the world origin
// (world = sensor frame), yaw 0, 10, ..., 350 degrees, each frame's crop a flat 4x4 patch.
Reenactment TurningClip(std::vector<int64_t> flagged_skeleton_frames = {}) {
  proto::ClipManifest manifest;
  manifest.flagged_skeleton_frames = std::move(flagged_skeleton_frames);
  manifest.color_camera = PinholeCamera::KinectLike();
  manifest.depth_camera = manifest.color_camera;
  manifest.radius_ratio = DefaultRadiusRatios();
  std::vector<proto::ClipFrame> frames;
  for (int d = 0; d < 360; d += 10) {
    proto::ClipFrame f;
    f.skeleton_in_world = testing::StandingPerson(3.0, d * M_PI / 180, true);
    f.color = ImageRgb8(4, 4, 3, 100);
    f.depth = ImageDepthMm(4, 4, 1, 3000);
    f.mask = ImageGray8(4, 4, 1, 255);
    frames.push_back(f);
  }
  manifest.frame_count = static_cast<int64_t>(frames.size());
  return Reenactment(manifest, std::move(frames));
}

TEST(Reenactment, ViewerAtTheSensorReusesTheSameFrameWithIdentityMapping) {
  const Reenactment r = TurningClip();
  const PinholeCamera cam = PinholeCamera::KinectLike();
  for (int k : {0, 7, 20}) {
    const ReenactedFrame f = r.Build(k, cam, Eigen::Isometry3d::Identity(), [](int n) { return n; });
    EXPECT_EQ(f.texture_frame, k);
    ASSERT_EQ(f.draw.cylinders.size(), static_cast<size_t>(kBodyPartCount));
    for (const CylinderDraw& c : f.draw.cylinders) {
      ASSERT_EQ(c.candidates.size(), 1u);
      EXPECT_EQ(c.candidates[0].texture, k);
      EXPECT_LT((c.candidates[0].stored_from_viewer - Eigen::Matrix4d::Identity()).norm(), 1e-9);
    }
  }
}

TEST(Reenactment, NamesTheBodyPartOfEveryCylinderAndSkipsMissingParts) {
  proto::ClipManifest manifest;
  manifest.color_camera = PinholeCamera::KinectLike();
  manifest.radius_ratio = DefaultRadiusRatios();
  proto::ClipFrame f;
  f.skeleton_in_world = testing::StandingPerson(3.0, 0, true);
  f.skeleton_in_world.confidence[Index(Joint::kLeftElbow)] = 0;  // no left upper arm, forearm
  f.color = ImageRgb8(4, 4, 3, 100);
  f.depth = ImageDepthMm(4, 4, 1, 3000);
  f.mask = ImageGray8(4, 4, 1, 255);
  manifest.frame_count = 1;
  const Reenactment r(manifest, {f});
  const ReenactedFrame out = r.Build(0, PinholeCamera::KinectLike(), Eigen::Isometry3d::Identity(),
                                     [](int n) { return n; });
  ASSERT_EQ(out.cylinder_parts.size(), out.draw.cylinders.size());
  ASSERT_EQ(out.cylinder_parts.size(), static_cast<size_t>(kBodyPartCount - 2));
  for (size_t i = 0; i < out.cylinder_parts.size(); ++i) {
    const BodyPart p = out.cylinder_parts[i];
    EXPECT_NE(p, BodyPart::kLeftUpperArm);
    EXPECT_NE(p, BodyPart::kLeftForearm);
    // The cylinder's axis runs between the part's own joints (world = viewer here).
    const auto [ja, jb] = PartJoints(p);
    const CylinderDraw& c = out.draw.cylinders[i];
    EXPECT_LT((c.a - f.skeleton_in_world[ja]).norm(), 1e-12) << PartName(p);
    EXPECT_LT((c.b - f.skeleton_in_world[jb]).norm(), 1e-12) << PartName(p);
  }
}

TEST(Reenactment, ViewerBehindTheSubjectSeesTheFrameTurnedHalfWay) {
  const Reenactment r = TurningClip();
  // Viewer on the far side: turned 180 degrees about the vertical (-y) axis through the
  // subject at z = 3, looking back at it.
  Eigen::Isometry3d world_from_viewer = Eigen::Isometry3d::Identity();
  world_from_viewer.translate(Eigen::Vector3d(0, 0, 3));
  world_from_viewer.rotate(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()));
  world_from_viewer.translate(Eigen::Vector3d(0, 0, -3));
  const ReenactedFrame f =
      r.Build(2, PinholeCamera::KinectLike(), world_from_viewer.inverse(), [](int n) { return n; });
  EXPECT_EQ(f.texture_frame, 2 + 18);  // 20 + 180 degrees
}

TEST(Reenactment, FramesWithFlaggedSkeletonsAreNeverChosen) {
  // At the sensor the best frame for output frame 2 is frame 2 itself (the test above);
  // flagged, it must give way to a neighbour 10 degrees off.
  const Reenactment r = TurningClip({2});
  const int chosen = r.Build(2, PinholeCamera::KinectLike(), Eigen::Isometry3d::Identity(),
                             [](int n) { return n; })
                         .texture_frame;
  EXPECT_TRUE(chosen == 1 || chosen == 3) << chosen;
}

TEST(Reenactment, FramesWithoutVisibleSubjectAreNeverChosen) {
  proto::ClipManifest manifest;
  manifest.color_camera = PinholeCamera::KinectLike();
  manifest.radius_ratio = DefaultRadiusRatios();
  std::vector<proto::ClipFrame> frames(2);
  for (auto& f : frames) {
    f.skeleton_in_world = testing::StandingPerson(3.0, 0, true);
    f.color = ImageRgb8(4, 4, 3, 0);
    f.depth = ImageDepthMm(4, 4, 1, 0);
    f.mask = ImageGray8(4, 4, 1, 0);
  }
  frames[1].mask = ImageGray8(4, 4, 1, 255);
  manifest.frame_count = 2;
  const Reenactment r(manifest, std::move(frames));
  EXPECT_EQ(r.Build(0, PinholeCamera::KinectLike(), Eigen::Isometry3d::Identity(),
                    [](int n) { return n; }).texture_frame, 1);
}

}  // namespace
}  // namespace reenact::viewer
