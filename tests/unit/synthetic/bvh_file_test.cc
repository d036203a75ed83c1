#include "synthetic/bvh_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

bool Contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// A root with 6 channels (order given), a child B one unit along the root's x axis with three
// rotation channels (order given), and an End Site two units along B's y axis.
std::string TwoJoints(const std::string& root_channels, const std::string& b_channels,
                      const std::string& frame) {
  return "HIERARCHY\n"
         "ROOT A\n"
         "{\n"
         "  OFFSET 0 0 0\n"
         "  CHANNELS 6 " +
         root_channels +
         "\n"
         "  JOINT B\n"
         "  {\n"
         "    OFFSET 1 0 0\n"
         "    CHANNELS 3 " +
         b_channels +
         "\n"
         "    End Site\n"
         "    {\n"
         "      OFFSET 0 2 0\n"
         "    }\n"
         "  }\n"
         "}\n"
         "MOTION\n"
         "Frames: 1\n"
         "Frame Time: 0.1\n" +
         frame + "\n";
}

constexpr const char* kPosZyx = "Xposition Yposition Zposition Zrotation Yrotation Xrotation";
constexpr const char* kZyx = "Zrotation Yrotation Xrotation";

void ExpectNear(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  EXPECT_LT((a - b).norm(), 1e-9) << a.transpose() << " vs " << b.transpose();
}

TEST(BvhFile, ParsesTheHierarchy) {
  const auto clip = ParseBvh(TwoJoints(kPosZyx, kZyx, "0 0 0 0 0 0 0 0 0"));
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  ASSERT_EQ(clip->joints.size(), 3u);
  EXPECT_EQ(clip->joints[0].name, "A");
  EXPECT_EQ(clip->joints[0].parent, -1);
  EXPECT_EQ(clip->joints[1].name, "B");
  EXPECT_EQ(clip->joints[1].parent, 0);
  EXPECT_EQ(clip->joints[1].first_channel, 6);
  EXPECT_TRUE(clip->joints[2].end_site);
  EXPECT_EQ(clip->joints[2].parent, 1);
  EXPECT_EQ(clip->channel_count, 9);
  EXPECT_EQ(clip->frame_count(), 1);
  EXPECT_DOUBLE_EQ(clip->frame_time_s, 0.1);
  EXPECT_EQ(clip->NamedJointNames(), (std::vector<std::string>{"A", "B"}));
}

TEST(BvhFile, RestPoseIsTheSumOfOffsetsPlusRootPosition) {
  const auto clip = ParseBvh(TwoJoints(kPosZyx, kZyx, "1 2 3 0 0 0 0 0 0"));
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  const auto p = BvhJointPositions(*clip, 0);
  ExpectNear(p[0], {1, 2, 3});
  ExpectNear(p[1], {2, 2, 3});
  ExpectNear(p[2], {2, 4, 3});
}

TEST(BvhFile, RootRotationTurnsTheChildren) {
  // Zrotation 90: x -> y, y -> -x. B = root + (0, 1, 0); End = B + Rz90 (0, 2, 0) = B - 2x.
  const auto clip = ParseBvh(TwoJoints(kPosZyx, kZyx, "1 2 3 90 0 0 0 0 0"));
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  const auto p = BvhJointPositions(*clip, 0);
  ExpectNear(p[1], {1, 3, 3});
  ExpectNear(p[2], {-1, 3, 3});
}

TEST(BvhFile, ChildRotationComposesWithTheParents) {
  // Root Rz(90), B Xrotation 90 (B's own x axis = world y): B's y axis goes to world z, so
  // End = B + 2 z.
  const auto clip = ParseBvh(TwoJoints(kPosZyx, kZyx, "0 0 0 90 0 0 0 0 90"));
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  const auto p = BvhJointPositions(*clip, 0);
  ExpectNear(p[1], {0, 1, 0});
  ExpectNear(p[2], {0, 1, 2});
}

TEST(BvhFile, ZyxChannelOrderIsRzRyRx) {
  // Channel values Z = 90, Y = 90, X = 0 in the order Zrotation Yrotation Xrotation give
  // R = Rz(90) Ry(90); B's offset (1, 0, 0): Ry(90) x = -z, Rz(90) (-z) = -z.
  const auto zyx = ParseBvh(TwoJoints(kPosZyx, kZyx, "0 0 0 90 90 0 0 0 0"));
  ASSERT_TRUE(zyx.ok()) << zyx.error().message;
  ExpectNear(BvhJointPositions(*zyx, 0)[1], {0, 0, -1});
  // The same angles listed X Y Z: R = Rx(0) Ry(90) Rz(90); Rz(90) x = y, Ry(90) y = y.
  const auto xyz = ParseBvh(TwoJoints("Xposition Yposition Zposition Xrotation Yrotation Zrotation",
                                      kZyx, "0 0 0 0 90 90 0 0 0"));
  ASSERT_TRUE(xyz.ok()) << xyz.error().message;
  ExpectNear(BvhJointPositions(*xyz, 0)[1], {0, 1, 0});
}

TEST(BvhFile, ZxyChildOrderAsInTheCmuArms) {
  // B with Zrotation Xrotation Yrotation = (0, 90, 90): R_B = Rx(90) Ry(90). End offset
  // (0, 2, 0): Ry(90) keeps y, Rx(90) y = z: End = B + (0, 0, 2). In Z Y X order the same
  // numbers mean Rz(0) Ry(90) Rx(90): Rx(90) y = z, Ry(90) z = x: End = B + (2, 0, 0).
  const auto zxy =
      ParseBvh(TwoJoints(kPosZyx, "Zrotation Xrotation Yrotation", "0 0 0 0 0 0 0 90 90"));
  ASSERT_TRUE(zxy.ok()) << zxy.error().message;
  ExpectNear(BvhJointPositions(*zxy, 0)[2], {1, 0, 2});
  const auto zyx = ParseBvh(TwoJoints(kPosZyx, kZyx, "0 0 0 0 0 0 0 90 90"));
  ASSERT_TRUE(zyx.ok()) << zyx.error().message;
  ExpectNear(BvhJointPositions(*zyx, 0)[2], {3, 0, 0});
}

TEST(BvhFile, ArbitraryRotationMatchesTheMatrixProduct) {
  const double z = 30, y = -50, x = 20;
  const auto clip = ParseBvh(TwoJoints(kPosZyx, kZyx,
                                       "0.5 -1 2 " + std::to_string(z) + " " + std::to_string(y) +
                                           " " + std::to_string(x) + " 0 0 0"));
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  const double d = M_PI / 180;
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(z * d, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(y * d, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(x * d, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  const auto t = BvhJointTransforms(*clip, 0);
  EXPECT_LT((t[0].linear() - r).norm(), 1e-9);
  ExpectNear(t[1].translation(), Eigen::Vector3d(0.5, -1, 2) + r * Eigen::Vector3d(1, 0, 0));
  ExpectNear(t[2].translation(), t[1].translation() + r * Eigen::Vector3d(0, 2, 0));
}

TEST(BvhFile, PositionChannelsAddToTheOffset) {
  const std::string text =
      "HIERARCHY\nROOT R\n{\n OFFSET 10 0 0\n CHANNELS 3 Xposition Yposition Zposition\n"
      " JOINT S\n {\n  OFFSET 0 1 0\n  CHANNELS 3 Yposition Xrotation Zposition\n"
      "  End Site\n  {\n   OFFSET 0 0 1\n  }\n }\n}\n"
      "MOTION\nFrames: 2\nFrame Time: 0.5\n1 2 3 0 0 0\n0 0 0 0.5 90 2\n";
  const auto clip = ParseBvh(text);
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  ExpectNear(BvhJointPositions(*clip, 0)[0], {11, 2, 3});
  ExpectNear(BvhJointPositions(*clip, 0)[1], {11, 3, 3});
  // Frame 1: S = (10, 1.5, 0), then Rx(90), then 2 along the rotated z (= -y): (10, -0.5, 0);
  // End = S + Rx(90) z = S - y.
  const auto p = BvhJointPositions(*clip, 1);
  ExpectNear(p[1], {10, -0.5, 0});
  ExpectNear(p[2], {10, -1.5, 0});
}

TEST(BvhFile, AcceptsCrlfMultipleRootsAndBlankTrailingLines) {
  const std::string text =
      "HIERARCHY\r\nROOT P\r\n{\r\nOFFSET 1 0 0\r\nCHANNELS 0\r\n}\r\n"
      "ROOT Q\r\n{\r\nOFFSET 0 1 0\r\nCHANNELS 1 Yposition\r\n}\r\n"
      "MOTION\r\nFrames: 1\r\nFrame Time: 0.04\r\n2.5\r\n\r\n\r\n";
  const auto clip = ParseBvh(text);
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  ASSERT_EQ(clip->joints.size(), 2u);
  EXPECT_EQ(clip->joints[1].parent, -1);
  ExpectNear(BvhJointPositions(*clip, 0)[1], {0, 3.5, 0});
}

TEST(BvhFile, FrameOutOfRangeThrows) {
  const auto clip = ParseBvh(TwoJoints(kPosZyx, kZyx, "0 0 0 0 0 0 0 0 0"));
  ASSERT_TRUE(clip.ok());
  EXPECT_THROW(BvhJointPositions(*clip, 1), CheckError);
  EXPECT_THROW(BvhJointPositions(*clip, -1), CheckError);
}

// --- malformed input: one test each; every message names the line ---

Error ParseError(const std::string& text) {
  const auto clip = ParseBvh(text, "x.bvh");
  EXPECT_FALSE(clip.ok());
  return clip.ok() ? Error{} : clip.error();
}

const std::string kGood = TwoJoints(kPosZyx, kZyx, "0 0 0 0 0 0 0 0 0");

std::string Replace(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

TEST(BvhFileErrors, TruncatedFrames) {
  const std::string text = Replace(kGood, "Frames: 1", "Frames: 3");
  const Error e = ParseError(text);
  EXPECT_EQ(e.code, "corrupt");
  EXPECT_TRUE(Contains(e.message, "truncated")) << e.message;
  EXPECT_TRUE(Contains(e.message, "x.bvh:")) << e.message;
}

TEST(BvhFileErrors, TruncatedHierarchy) {
  const Error e = ParseError(kGood.substr(0, kGood.find("    End Site")));
  EXPECT_TRUE(Contains(e.message, "no MOTION section")) << e.message;
}

TEST(BvhFileErrors, MissingMotion) {
  const Error e = ParseError(Replace(kGood, "MOTION", "MOTON"));
  EXPECT_TRUE(Contains(e.message, "no MOTION section")) << e.message;
}

TEST(BvhFileErrors, BadNumberInAFrame) {
  const Error e = ParseError(Replace(kGood, "0 0 0 0 0 0 0 0 0\n", "0 0 0 0 0 0 0 0 1.2.3\n"));
  EXPECT_TRUE(Contains(e.message, "x.bvh:19: '1.2.3' in frame 0 is not a finite number"))
      << e.message;
}

TEST(BvhFileErrors, NonFiniteNumberInAFrame) {
  const Error e = ParseError(Replace(kGood, "0 0 0 0 0 0 0 0 0\n", "0 0 0 0 0 0 0 0 nan\n"));
  EXPECT_TRUE(Contains(e.message, "x.bvh:19:")) << e.message;
}

TEST(BvhFileErrors, BadNumberInAnOffset) {
  const Error e = ParseError(Replace(kGood, "OFFSET 1 0 0", "OFFSET 1 zero 0"));
  EXPECT_TRUE(Contains(e.message, "x.bvh:8: 'zero' is not a finite number")) << e.message;
}

TEST(BvhFileErrors, FrameValueCountDiffersFromChannels) {
  const Error e = ParseError(Replace(kGood, "0 0 0 0 0 0 0 0 0\n", "0 0 0 0 0 0 0 0\n"));
  EXPECT_TRUE(Contains(e.message, "x.bvh:19: frame 0 has 8 values but the hierarchy declares 9"))
      << e.message;
}

TEST(BvhFileErrors, ChannelsCountDiffersFromTheListedNames) {
  const Error e = ParseError(Replace(kGood, "CHANNELS 3", "CHANNELS 4"));
  EXPECT_TRUE(Contains(e.message, "x.bvh:9: CHANNELS declares 4 channels but lists 3"))
      << e.message;
}

TEST(BvhFileErrors, UnknownChannel) {
  const Error e = ParseError(Replace(kGood, "Zrotation Yrotation Xrotation\n    End",
                                     "Zrotation Yrotation Wrotation\n    End"));
  EXPECT_TRUE(Contains(e.message, "x.bvh:9: unknown channel 'Wrotation'")) << e.message;
}

TEST(BvhFileErrors, RepeatedChannel) {
  const Error e = ParseError(Replace(kGood, "Zrotation Yrotation Xrotation\n    End",
                                     "Zrotation Yrotation Zrotation\n    End"));
  EXPECT_TRUE(Contains(e.message, "listed twice")) << e.message;
}

TEST(BvhFileErrors, ZeroFrames) {
  const Error e = ParseError(Replace(kGood, "Frames: 1", "Frames: 0"));
  EXPECT_TRUE(Contains(e.message, "x.bvh:17: the clip has 0 frames")) << e.message;
}

TEST(BvhFileErrors, MissingFramesLine) {
  const Error e = ParseError(Replace(kGood, "Frames: 1\n", ""));
  EXPECT_TRUE(Contains(e.message, "x.bvh:17: expected 'Frames: N'")) << e.message;
}

TEST(BvhFileErrors, NonPositiveFrameTime) {
  const Error e = ParseError(Replace(kGood, "Frame Time: 0.1", "Frame Time: 0"));
  EXPECT_TRUE(Contains(e.message, "x.bvh:18: 'Frame Time:' needs a positive")) << e.message;
}

TEST(BvhFileErrors, MoreFrameLinesThanDeclared) {
  const Error e = ParseError(kGood + "0 0 0 0 0 0 0 0 0\n");
  EXPECT_TRUE(Contains(e.message, "x.bvh:20: more frame lines")) << e.message;
}

TEST(BvhFileErrors, MissingHierarchyKeyword) {
  const Error e = ParseError(Replace(kGood, "HIERARCHY", "HIERARCHIE"));
  EXPECT_TRUE(Contains(e.message, "x.bvh:1: expected 'HIERARCHY'")) << e.message;
}

TEST(BvhFileErrors, UnexpectedTokenInAJoint) {
  const Error e = ParseError(Replace(kGood, "  JOINT B", "  JIONT B"));
  EXPECT_TRUE(Contains(e.message, "x.bvh:6: expected 'JOINT', 'End Site' or '}'")) << e.message;
}

TEST(BvhFileErrors, MissingFile) {
  const auto clip = ReadBvhFile("/nonexistent/walk.bvh");
  ASSERT_FALSE(clip.ok());
  EXPECT_EQ(clip.error().code, "not_found");
  EXPECT_TRUE(Contains(clip.error().message, "/nonexistent/walk.bvh")) << clip.error().message;
}

}  // namespace
}  // namespace reenact::capture
