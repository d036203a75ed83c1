#include "synthetic/bvh_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "common/skeleton/joint_maps.h"

namespace reenact::capture {
namespace {

bool Contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// A hand-built rig with common joint names, in centimetres, standing in its rest pose facing
// +z with its left along +x (the BVH convention). Joint heights above the floor (y):
// hips 100, ankles 8, spine 120, neck 150, head 162, shoulders 145 (18 lateral), elbows 115,
// hands 90; hips 10 lateral. Root channels: X/Y/Z position, then Yrotation (a turn).
std::string Rig(const std::string& frames, int frame_count, double frame_time) {
  std::ostringstream s;
  s << "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n"
       " CHANNELS 4 Xposition Yposition Zposition Yrotation\n";
  for (const char* side : {"Left", "Right"}) {
    const double x = std::string(side) == "Left" ? 1 : -1;
    s << " JOINT " << side << "UpLeg\n {\n  OFFSET " << 10 * x << " -5 0\n  CHANNELS 0\n"
      << "  JOINT " << side << "Leg\n  {\n   OFFSET 0 -45 0\n   CHANNELS 0\n"
      << "   JOINT " << side << "Foot\n   {\n    OFFSET 0 -42 0\n    CHANNELS 0\n"
      << "    End Site\n    {\n     OFFSET 0 -8 12\n    }\n   }\n  }\n }\n";
  }
  s << " JOINT Spine\n {\n  OFFSET 0 20 0\n  CHANNELS 0\n"
       "  JOINT Neck\n  {\n   OFFSET 0 30 0\n   CHANNELS 0\n"
       "   JOINT Head\n   {\n    OFFSET 0 12 0\n    CHANNELS 0\n"
       "    End Site\n    {\n     OFFSET 0 10 0\n    }\n   }\n  }\n";
  for (const char* side : {"Left", "Right"}) {
    const double x = std::string(side) == "Left" ? 1 : -1;
    s << "  JOINT " << side << "Arm\n  {\n   OFFSET " << 18 * x << " 25 0\n   CHANNELS 0\n"
      << "   JOINT " << side << "ForeArm\n   {\n    OFFSET 0 -30 0\n    CHANNELS 0\n"
      << "    JOINT " << side << "Hand\n    {\n     OFFSET 0 -25 0\n     CHANNELS 0\n"
      << "     End Site\n     {\n      OFFSET 0 -8 0\n     }\n    }\n   }\n  }\n";
  }
  s.precision(17);
  s << " }\n}\nMOTION\nFrames: " << frame_count << "\nFrame Time: " << frame_time << "\n" << frames;
  return s.str();
}

// 121 frames at 120 Hz: the subject, turned by `yaw_deg` about the vertical, walks 1 m/s
// straight ahead (along its own facing, R_y(yaw) (0, 0, 1)).
std::string WalkingRig(double yaw_deg) {
  std::ostringstream frames;
  frames.precision(17);
  const double yaw = yaw_deg * M_PI / 180;
  for (int f = 0; f <= 120; ++f) {
    const double d = 100.0 * f / 120;  // cm
    frames << d * std::sin(yaw) << " 100 " << d * std::cos(yaw) << " " << yaw_deg << "\n";
  }
  return Rig(frames.str(), 121, 1.0 / 120);
}

void ExpectNear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol = 1e-6) {
  EXPECT_LT((a - b).norm(), tol) << a.transpose() << " vs " << b.transpose();
}

TEST(BvhMotion, PlacesTheSubjectAtTheOriginFacingTheSensorOnTheFloor) {
  for (double yaw : {0.0, 30.0, -135.0}) {
    const auto clip = ParseBvh(WalkingRig(yaw));
    ASSERT_TRUE(clip.ok()) << clip.error().message;
    const auto motion = BvhToSkeletons(*clip);
    ASSERT_TRUE(motion.ok()) << motion.error().message;
    EXPECT_EQ(motion->joint_set, "by_name");
    EXPECT_DOUBLE_EQ(motion->metres_per_unit, 0.01);  // head to ankle 1.54 units*100
    // 1 s at 30 Hz: frames 0..30.
    ASSERT_EQ(motion->skeletons.size(), 31u);
    for (int k = 0; k <= 30; ++k) {
      const Skeleton& s = motion->skeletons[k];
      ASSERT_TRUE(s.Complete());
      // Facing world -y, left = world +x, walking forward at 1 m/s; ankles at 0.08 m.
      const double y = -k / 30.0;
      ExpectNear(s[Joint::kWaist], {0, y, 1.0});
      ExpectNear(s[Joint::kTorso], {0, y, 1.2});
      ExpectNear(s[Joint::kNeck], {0, y, 1.5});
      ExpectNear(s[Joint::kHead], {0, y, 1.62});
      ExpectNear(s[Joint::kLeftShoulder], {0.18, y, 1.45});
      ExpectNear(s[Joint::kRightElbow], {-0.18, y, 1.15});
      ExpectNear(s[Joint::kLeftHand], {0.18, y, 0.90});
      ExpectNear(s[Joint::kLeftHip], {0.10, y, 0.95});
      ExpectNear(s[Joint::kRightKnee], {-0.10, y, 0.50});
      ExpectNear(s[Joint::kRightFoot], {-0.10, y, 0.08});
    }
  }
}

TEST(BvhMotion, ResamplesJointPositionsLinearly) {
  // 10 Hz source, 3 frames; the root's x goes 0, 30, 90 cm. At 30 Hz: 7 frames at source
  // times 0, 1/30, ..., 0.2; frame 1 lies 1/3 of the way from source frame 0 to 1 and frame
  // 5 two thirds of the way from 1 to 2. World x = file x (no turn: the rig faces +z).
  const auto clip = ParseBvh(Rig("0 100 0 0\n30 100 0 0\n90 100 0 0\n", 3, 0.1));
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  const auto motion = BvhToSkeletons(*clip);
  ASSERT_TRUE(motion.ok()) << motion.error().message;
  ASSERT_EQ(motion->skeletons.size(), 7u);
  const double expected_cm[7] = {0, 10, 20, 30, 50, 70, 90};
  for (int k = 0; k < 7; ++k)
    EXPECT_NEAR(motion->skeletons[k][Joint::kWaist].x(), expected_cm[k] / 100, 1e-9) << k;
}

TEST(BvhMotion, OutputRateIsAnOption) {
  const auto clip = ParseBvh(WalkingRig(0));
  ASSERT_TRUE(clip.ok());
  BvhMotionOptions options;
  options.frame_rate_hz = 60;
  options.metres_per_unit = 0.02;  // an explicit unit wins over the guess
  options.ankle_height_m = 0;
  const auto motion = BvhToSkeletons(*clip, options);
  ASSERT_TRUE(motion.ok());
  ASSERT_EQ(motion->skeletons.size(), 61u);
  ExpectNear(motion->skeletons[60][Joint::kWaist], {0, -2.0, 0.92 * 2});
  EXPECT_NEAR(motion->skeletons[0][Joint::kLeftFoot].z(), 0, 1e-9);
}

TEST(BvhMotion, UnknownRigIsAnError) {
  std::string text = Rig("0 100 0 0\n", 1, 0.1);
  for (const char* from : {"LeftForeArm", "RightForeArm"}) {
    const size_t at = text.find(from);
    text.replace(at, std::string(from).size(), "Gizmo");
  }
  // Two joints named Gizmo collide after normalisation only if equal: rename the second.
  text.replace(text.rfind("Gizmo"), 5, "Widget");
  const auto clip = ParseBvh(text);
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  const auto motion = BvhToSkeletons(*clip);
  ASSERT_FALSE(motion.ok());
  EXPECT_EQ(motion.error().code, "unsupported");
  EXPECT_TRUE(Contains(motion.error().message, "lacks joints for our l_elbow, r_elbow"))
      << motion.error().message;
  EXPECT_TRUE(Contains(motion.error().message, "Gizmo")) << motion.error().message;
}

TEST(BvhMotion, RigWithNoKnownNameIsAnError) {
  const auto clip = ParseBvh(
      "HIERARCHY\nROOT Thing\n{\nOFFSET 0 0 0\nCHANNELS 0\n}\nMOTION\nFrames: 1\n"
      "Frame Time: 0.1\n\n");
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  const auto motion = BvhToSkeletons(*clip);
  ASSERT_FALSE(motion.ok());
  EXPECT_EQ(motion.error().code, "unsupported");
  EXPECT_TRUE(Contains(motion.error().message, "Thing")) << motion.error().message;
}

TEST(BvhMotion, UndefinedFacingIsAnError) {
  // Every joint at the same point (all offsets zero): no left-right direction.
  std::string text = Rig("0 100 0 0\n", 1, 0.1);
  std::string flat;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    flat += (line.find("OFFSET") != std::string::npos ? "OFFSET 0 0 0" : line) + "\n";
  const auto clip = ParseBvh(flat);
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  const auto motion = BvhToSkeletons(*clip);
  ASSERT_FALSE(motion.ok());
  EXPECT_TRUE(Contains(motion.error().message, "cannot tell which way the subject faces"))
      << motion.error().message;
}

TEST(BvhMotion, LoadNamesThePathInErrors) {
  const auto missing = LoadBvhMotion("/nonexistent/walk.bvh");
  ASSERT_FALSE(missing.ok());
  EXPECT_TRUE(Contains(missing.error().message, "/nonexistent/walk.bvh"));
}

// --- the real CMU takes ---

std::filesystem::path Mocap(const std::string& name) {
  return std::filesystem::path(REENACT_SHARED_DATA_DIR) / "mocap" / name;
}

class CmuWalk : public testing::TestWithParam<std::string> {};

TEST_P(CmuWalk, IsAPlausibleHumanWalk) {
  const std::filesystem::path path = Mocap(GetParam());
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not present";
  const auto clip = ReadBvhFile(path);
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  EXPECT_EQ(clip->NamedJointNames(), CmuBvhJoints().source_names);
  EXPECT_NEAR(clip->frame_time_s, 1.0 / 120, 1e-6);
  const auto motion = BvhToSkeletons(*clip);
  ASSERT_TRUE(motion.ok()) << motion.error().message;
  EXPECT_EQ(motion->joint_set, "cmu_bvh");
  EXPECT_NEAR(motion->metres_per_unit, 0.0254 / 0.45, 1e-12);
  // Frames 0 .. floor(duration * 30) (the header's rounding rule).
  EXPECT_EQ(
      static_cast<int>(motion->skeletons.size()),
      static_cast<int>(std::floor((clip->frame_count() - 1) * clip->frame_time_s * 30 + 1e-3)) + 1);

  const Skeleton& first = motion->skeletons.front();
  // README: hips about 0.95 m above the floor.
  EXPECT_NEAR(first[Joint::kWaist].z(), 0.95, 0.05);
  EXPECT_NEAR(first[Joint::kWaist].x(), 0, 1e-9);
  EXPECT_NEAR(first[Joint::kWaist].y(), 0, 1e-9);
  // Facing world -y: the left side is at +x.
  EXPECT_GT(first[Joint::kLeftHip].x(), first[Joint::kRightHip].x());
  EXPECT_GT(first[Joint::kLeftShoulder].x(), first[Joint::kRightShoulder].x());

  // Bones are rigid: each mapped bone's length is constant over the clip and human-sized
  // (adult limb bones: 0.15-0.5 m).
  const std::pair<Joint, Joint> bones[] = {
      {Joint::kLeftHip, Joint::kLeftKnee},         {Joint::kLeftKnee, Joint::kLeftFoot},
      {Joint::kRightHip, Joint::kRightKnee},       {Joint::kRightKnee, Joint::kRightFoot},
      {Joint::kLeftShoulder, Joint::kLeftElbow},   {Joint::kLeftElbow, Joint::kLeftHand},
      {Joint::kRightShoulder, Joint::kRightElbow}, {Joint::kRightElbow, Joint::kRightHand}};
  for (auto [a, b] : bones) {
    const double length = (first[a] - first[b]).norm();
    EXPECT_GT(length, 0.15) << JointName(a);  // CMU's wrist: forearms of 0.18-0.19 m
    EXPECT_LT(length, 0.5) << JointName(a);
    for (const Skeleton& s : motion->skeletons)
      EXPECT_NEAR((s[a] - s[b]).norm(), length, 1e-3) << JointName(a);
  }

  // Feet stay on the floor: the lower ankle never sinks below 3 cm nor, at the start, sits
  // anywhere but at the ankle height; the head stays in a standing person's range.
  double lowest = INFINITY, farthest = 0;
  for (const Skeleton& s : motion->skeletons) {
    lowest = std::min({lowest, s[Joint::kLeftFoot].z(), s[Joint::kRightFoot].z()});
    farthest = std::max(farthest, s[Joint::kWaist].head<2>().norm());
  }
  EXPECT_GT(lowest, 0.03);
  EXPECT_NEAR(std::min(first[Joint::kLeftFoot].z(), first[Joint::kRightFoot].z()), 0.08, 1e-9);
  // The walk goes forward (towards world -y) for more than a metre and a half.
  const Skeleton& last = motion->skeletons.back();
  EXPECT_LT(last[Joint::kWaist].y(), -1.5);
  EXPECT_GT(farthest, 1.5);
}

INSTANTIATE_TEST_SUITE_P(Takes, CmuWalk,
                         testing::Values("cmu-131_01-walk.bvh", "cmu-131_02-walk.bvh"));

}  // namespace
}  // namespace reenact::capture
