// Reenactment with per-part texture selection (issue 9): which stored frames each cylinder
// gets, with what weights, and where a part cut off by the crop is not taken from.

#include <gtest/gtest.h>

#include <cmath>

#include "common/error/check.h"
#include "tests/unit/common/test_skeletons.h"
#include "viewer-client/play/reenactment.h"

namespace reenact::viewer {
namespace {

double Deg(double d) { return d * M_PI / 180; }

// Static sensor at the world origin (world = sensor frame). Frames 0-3: arms out at yaw 0,
// 90, 180, 270 degrees; frames 4-7: the same with arms down. Each crop is the whole image,
// except where crop_y_of_frame moves it down (cutting off what lies above).
Reenactment Clip(int frame_with_low_crop = -1, int crop_y = 0) {
  proto::ClipManifest manifest;
  manifest.color_camera = PinholeCamera::KinectLike();
  manifest.depth_camera = manifest.color_camera;
  manifest.radius_ratio = DefaultRadiusRatios();
  std::vector<proto::ClipFrame> frames;
  for (bool arms_out : {true, false})
    for (int d = 0; d < 360; d += 90) {
      proto::ClipFrame f;
      f.skeleton_in_world = testing::StandingPerson(3.0, Deg(d), arms_out);
      const int n = static_cast<int>(frames.size());
      f.crop_y = n == frame_with_low_crop ? crop_y : 0;
      const int h = manifest.color_camera.height - f.crop_y;
      f.color = ImageRgb8(manifest.color_camera.width, h, 3, 100);
      f.depth = ImageDepthMm(manifest.color_camera.width, h, 1, 3000);
      f.mask = ImageGray8(manifest.color_camera.width, h, 1, 255);
      frames.push_back(f);
    }
  manifest.frame_count = static_cast<int64_t>(frames.size());
  return Reenactment(manifest, std::move(frames));
}

// Facing the sensor, right arm out, left arm down.
Skeleton LeftArmDown() {
  Skeleton s = testing::StandingPerson(3.0, 0, true);
  const Skeleton down = testing::StandingPerson(3.0, 0, false);
  for (Joint j : {Joint::kLeftElbow, Joint::kLeftHand}) s.Set(j, down[j]);
  return s;
}

const CylinderDraw& Part(const ReenactedFrame& f, BodyPart p) {
  for (size_t i = 0; i < f.cylinder_parts.size(); ++i)
    if (f.cylinder_parts[i] == p) return f.draw.cylinders[i];
  throw std::runtime_error("part not drawn");
}

constexpr TexturingOptions kPerPart{.selection = TextureSelection::kPerPart};

TEST(ReenactmentTexturing, EachPartIsTexturedFromTheFrameThatShowsIt) {
  const Reenactment r = Clip();
  const auto identity = [](int n) { return n; };
  const ReenactedFrame whole = r.BuildPosed(0, LeftArmDown(), PinholeCamera::KinectLike(),
                                            Eigen::Isometry3d::Identity(), identity, {});
  const ReenactedFrame parts = r.BuildPosed(0, LeftArmDown(), PinholeCamera::KinectLike(),
                                            Eigen::Isometry3d::Identity(), identity, kPerPart);
  // Whole-body Eq. 5: one frame for every cylinder.
  for (const CylinderDraw& c : whole.draw.cylinders) {
    ASSERT_EQ(c.candidates.size(), 1u);
    EXPECT_EQ(c.candidates[0].texture, whole.texture_frame);
  }
  // Per part: the left arm from the arms-down frame facing the sensor (4), the right arm
  // from the arms-out one (0); the legs look the same in both (ties go to the lower index).
  EXPECT_EQ(Part(parts, BodyPart::kLeftForearm).candidates.at(0).texture, 4);
  EXPECT_EQ(Part(parts, BodyPart::kLeftUpperArm).candidates.at(0).texture, 4);
  EXPECT_EQ(Part(parts, BodyPart::kRightForearm).candidates.at(0).texture, 0);
  EXPECT_EQ(Part(parts, BodyPart::kLeftShin).candidates.at(0).texture, 0);
  EXPECT_EQ(parts.texture_frame, 0);  // the upper torso's
  // Facing the sensor, the frame's own cylinders: identity mappings.
  EXPECT_LT((Part(parts, BodyPart::kLeftForearm).candidates[0].stored_from_viewer -
             Eigen::Matrix4d::Identity())
                .norm(),
            1e-9);
}

TEST(ReenactmentTexturing, APartOutsideTheStoredCropIsTakenFromAnotherFrame) {
  // Frame 0's crop starts at row 200: the head (about 0.75 m above the waist, 3 m away) lies
  // above it, the legs inside.
  const Reenactment r = Clip(0, 200);
  const ReenactedFrame f = r.BuildPosed(
      0, r.frame(0).skeleton_in_world, PinholeCamera::KinectLike(), Eigen::Isometry3d::Identity(),
      [](int n) { return n; }, kPerPart);
  EXPECT_NE(Part(f, BodyPart::kHead).candidates.at(0).texture, 0);
  EXPECT_EQ(Part(f, BodyPart::kLeftShin).candidates.at(0).texture, 0);
}

TEST(ReenactmentTexturing, SeveralCandidatesCarryWeightsAndUnloadableFramesAreDropped) {
  const Reenactment r = Clip();
  const TexturingOptions blend{.selection = TextureSelection::kPerPart,
                               .mode = TexturingMode::kBlendVisible,
                               .candidates = 3,
                               .hysteresis = 0.2};
  PartSelectionHistory history;
  const ReenactedFrame f = r.BuildPosed(
      0, testing::StandingPerson(3.0, Deg(30), true), PinholeCamera::KinectLike(),
      Eigen::Isometry3d::Identity(), [](int n) { return n == 5 ? -1 : n; }, blend, &history);
  for (const CylinderDraw& c : f.draw.cylinders) {
    EXPECT_EQ(c.texturing, TexturingMode::kBlendVisible);
    ASSERT_FALSE(c.candidates.empty());
    EXPECT_LE(c.candidates.size(), 3u);
    for (const TextureCandidate& t : c.candidates) {
      EXPECT_NE(t.texture, 5);  // the caller could not load frame 5
      EXPECT_GE(t.weight, 0.0);
    }
    EXPECT_GE(c.candidates[0].weight, c.candidates.back().weight);
  }
  // The choice is remembered for the next output frame.
  EXPECT_EQ(history.previous[Index(BodyPart::kHead)].size(), 3u);
}

TEST(ReenactmentTexturing, OptionsAreChecked) {
  EXPECT_THROW((TexturingOptions{.candidates = 2}.Check()), CheckError);  // whole body
  EXPECT_THROW((TexturingOptions{.selection = TextureSelection::kPerPart, .candidates = 0}.Check()),
               CheckError);
  EXPECT_THROW((TexturingOptions{.selection = TextureSelection::kPerPart,
                                 .candidates = kMaxTextureCandidates + 1}
                    .Check()),
               CheckError);
  EXPECT_THROW((TexturingOptions{.hysteresis = 1}.Check()), CheckError);
  // Fallbacks: within the renderers' candidates, per part, with a visibility mode.
  constexpr TexturingOptions kFallback{.selection = TextureSelection::kPerPart,
                                       .mode = TexturingMode::kBlendVisible,
                                       .candidates = 3,
                                       .fallback_candidates = kMaxTextureCandidates - 3};
  EXPECT_NO_THROW(kFallback.Check());
  TexturingOptions bad = kFallback;
  bad.fallback_candidates = kMaxTextureCandidates - 2;
  EXPECT_THROW(bad.Check(), CheckError);
  bad = kFallback;
  bad.fallback_candidates = -1;
  EXPECT_THROW(bad.Check(), CheckError);
  bad = kFallback;
  bad.mode = TexturingMode::kFirst;
  EXPECT_THROW(bad.Check(), CheckError);
  bad = kFallback;
  bad.selection = TextureSelection::kWholeBody;
  bad.candidates = 1;
  EXPECT_THROW(bad.Check(), CheckError);
  EXPECT_THROW((TexturingOptions{.missing_joint_cost_m = -1}.Check()), CheckError);
  EXPECT_NO_THROW(kPerPart.Check());
  const Reenactment r = Clip();
  EXPECT_THROW(r.BuildPosed(
                   0, r.frame(0).skeleton_in_world, PinholeCamera::KinectLike(),
                   Eigen::Isometry3d::Identity(), [](int n) { return n; },
                   TexturingOptions{.candidates = 3}),
               CheckError);
}

}  // namespace
}  // namespace reenact::viewer
