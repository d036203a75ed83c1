// The small pieces of the frame sources: spec arguments, pose interpolation, frame checks,
// the TUM camera presets, and OpenFrameSource's dispatch.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "capture-client/source/frame_checks.h"
#include "capture-client/source/frame_source.h"
#include "capture-client/source/source_argument.h"
#include "capture-client/source/timed_trajectory.h"
#include "capture-client/source/tum_camera.h"
#include "common/geometry/rotation.h"

namespace reenact::capture {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(SourceArgument, SplitsPathAndOptions) {
  auto a =
      ParseSourceArgument("tum", "/data/seq?camera=fr1&undistort=none", {"camera", "undistort"});
  ASSERT_TRUE(a.ok()) << a.error().message;
  EXPECT_EQ(a->path, "/data/seq");
  EXPECT_EQ(a->options.at("camera"), "fr1");
  EXPECT_EQ(a->options.at("undistort"), "none");
  auto plain = ParseSourceArgument("tum", "/data/seq", {"camera"});
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(plain->path, "/data/seq");
  EXPECT_TRUE(plain->options.empty());
  auto marks = ParseSourceArgument("oni", "what?.oni?", {});
  ASSERT_TRUE(marks.ok());
  EXPECT_EQ(marks->path, "what?.oni");
}

TEST(SourceArgument, RejectsUnknownMalformedAndRepeatedOptions) {
  auto unknown = ParseSourceArgument("tum", "d?speed=2", {"camera", "undistort"});
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().code, "usage");
  EXPECT_NE(unknown.error().message.find("options: camera, undistort"), std::string::npos);
  auto bare = ParseSourceArgument("tum", "d?camera", {"camera"});
  ASSERT_FALSE(bare.ok());
  EXPECT_NE(bare.error().message.find("NAME=VALUE"), std::string::npos);
  auto twice = ParseSourceArgument("tum", "d?camera=fr1&camera=fr2", {"camera"});
  ASSERT_FALSE(twice.ok());
  EXPECT_NE(twice.error().message.find("twice"), std::string::npos);
  EXPECT_TRUE(*ParseBoolOption("oni", "registered", "yes"));
  EXPECT_FALSE(*ParseBoolOption("oni", "registered", "0"));
  EXPECT_FALSE(ParseBoolOption("oni", "registered", "maybe").ok());
}

TimedPose Sample(double t, Eigen::Vector3d p, double yaw) {
  return {t, p, Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()))};
}

TEST(InterpolatePose, LinearPositionAndSlerpRotation) {
  const std::vector<TimedPose> samples = {Sample(1.0, {0, 0, 0}, 0),
                                          Sample(2.0, {2, 4, -2}, kPi / 2)};
  const auto mid = InterpolatePose(samples, 1.25, 10);
  ASSERT_TRUE(mid.has_value());
  EXPECT_NEAR((mid->translation() - Eigen::Vector3d(0.5, 1, -0.5)).norm(), 0, 1e-12);
  const Eigen::Matrix3d expected =
      Eigen::AngleAxisd(kPi / 8, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_NEAR(RotationAngle(mid->linear() * expected.transpose()), 0, 1e-12);
  // At a sample's time: that sample.
  const auto at = InterpolatePose(samples, 2.0, 10);
  ASSERT_TRUE(at.has_value());
  EXPECT_NEAR((at->translation() - Eigen::Vector3d(2, 4, -2)).norm(), 0, 1e-15);
}

TEST(InterpolatePose, TakesTheShortArcWhateverTheQuaternionSign) {
  // q and -q are one rotation; the 90 deg turn must not become a 270 deg one.
  std::vector<TimedPose> samples = {Sample(0, {0, 0, 0}, 0), Sample(1, {0, 0, 0}, kPi / 2)};
  samples[1].rotation.coeffs() *= -1;
  const auto mid = InterpolatePose(samples, 0.5, 10);
  ASSERT_TRUE(mid.has_value());
  EXPECT_NEAR(RotationAngle(mid->linear()), kPi / 4, 1e-12);
}

TEST(InterpolatePose, DegenerateCasesHaveDefinedResults) {
  const std::vector<TimedPose> none;
  EXPECT_FALSE(InterpolatePose(none, 1.0, 1).has_value());
  const std::vector<TimedPose> one = {Sample(1.0, {1, 2, 3}, 0.3)};
  ASSERT_TRUE(InterpolatePose(one, 1.0, 1).has_value());
  EXPECT_NEAR((InterpolatePose(one, 1.0, 1)->translation() - Eigen::Vector3d(1, 2, 3)).norm(), 0,
              0);
  EXPECT_FALSE(InterpolatePose(one, 1.1, 1).has_value());
  const std::vector<TimedPose> two = {Sample(1.0, {0, 0, 0}, 0), Sample(2.0, {1, 0, 0}, 0)};
  EXPECT_FALSE(InterpolatePose(two, 0.999, 10).has_value());  // before the first
  EXPECT_FALSE(InterpolatePose(two, 2.001, 10).has_value());  // after the last
  EXPECT_FALSE(InterpolatePose(two, 1.5, 0.5).has_value());   // across a gap over the limit
  EXPECT_FALSE(InterpolatePose(two, std::numeric_limits<double>::quiet_NaN(), 10).has_value());
  // Two samples at one time: the first, never a division by zero.
  const std::vector<TimedPose> same = {Sample(1.0, {0, 0, 0}, 0), Sample(1.0, {5, 0, 0}, 0),
                                       Sample(2.0, {6, 0, 0}, 0)};
  const auto dup = InterpolatePose(same, 1.0, 10);
  ASSERT_TRUE(dup.has_value());
  EXPECT_TRUE(dup->translation().allFinite());
  EXPECT_EQ(dup->translation().x(), 0);
  const auto after_dup = InterpolatePose(same, 1.5, 10);
  ASSERT_TRUE(after_dup.has_value());
  EXPECT_NEAR(after_dup->translation().x(), 5.5, 1e-12);
}

TEST(FrameChecks, RegisteredPairNeedsOneSize) {
  const PinholeCamera camera{4, 3, 1, 1, 1.5, 1, {}};
  EXPECT_TRUE(CheckRegisteredPair(ImageRgb8(4, 3, 3), ImageDepthMm(4, 3, 1), camera, "f").ok());
  const Status mismatch =
      CheckRegisteredPair(ImageRgb8(4, 3, 3), ImageDepthMm(2, 3, 1), camera, "f");
  ASSERT_FALSE(mismatch.ok());
  EXPECT_EQ(mismatch.error().code, "corrupt");
  EXPECT_NE(mismatch.error().message.find("colour is 4x3 but depth is 2x3"), std::string::npos);
  EXPECT_FALSE(CheckRegisteredPair(ImageRgb8(4, 3, 1), ImageDepthMm(4, 3, 1), camera, "f").ok());
  EXPECT_FALSE(CheckRegisteredPair(ImageRgb8(8, 6, 3), ImageDepthMm(8, 6, 1), camera, "f").ok());
}

TEST(FrameChecks, DepthPresenceGuardFailsOnlyOnLeadingEmptyFrames) {
  const ImageDepthMm empty(4, 3, 1), some(4, 3, 1, 800);
  DepthPresenceGuard guard(3);
  EXPECT_TRUE(guard.Observe(empty, "s").ok());
  EXPECT_TRUE(guard.Observe(empty, "s").ok());
  const Status third = guard.Observe(empty, "s");
  ASSERT_FALSE(third.ok());
  EXPECT_EQ(third.error().code, "no_depth");

  DepthPresenceGuard recovers(3);
  EXPECT_TRUE(recovers.Observe(empty, "s").ok());
  EXPECT_TRUE(recovers.Observe(some, "s").ok());
  for (int i = 0; i < 10; ++i) EXPECT_TRUE(recovers.Observe(empty, "s").ok());
  EXPECT_TRUE(recovers.AtEnd("s").ok());

  DepthPresenceGuard short_stream(30);
  EXPECT_TRUE(short_stream.AtEnd("s").ok());  // no frames: nothing to judge
  EXPECT_TRUE(short_stream.Observe(empty, "s").ok());
  EXPECT_FALSE(short_stream.AtEnd("s").ok());
  EXPECT_EQ(CountDepthReadings(some), 12u);
}

TEST(TumCamera, PresetsNamesAndDetection) {
  const PinholeCamera fr1 = TumColorCamera(TumCamera::kFreiburg1);
  EXPECT_DOUBLE_EQ(fr1.fx, 517.3);  // the data README's values
  EXPECT_DOUBLE_EQ(fr1.distortion.k3, 1.1633);
  EXPECT_TRUE(TumColorCamera(TumCamera::kFreiburg3).distortion.IsZero());
  for (TumCamera c : {TumCamera::kFreiburg1, TumCamera::kFreiburg2, TumCamera::kFreiburg3}) {
    TumColorCamera(c).Check();
    EXPECT_EQ(*ParseTumCamera(TumCameraName(c)), c);
  }
  EXPECT_EQ(*ParseTumCamera("Freiburg2"), TumCamera::kFreiburg2);
  EXPECT_EQ(DetectTumCamera("rgbd_dataset_freiburg1_rpy"), TumCamera::kFreiburg1);
  EXPECT_EQ(DetectTumCamera("tum-fr3-office"), TumCamera::kFreiburg3);
  EXPECT_EQ(DetectTumCamera("desk"), std::nullopt);
  EXPECT_EQ(DetectTumCamera("fr1_vs_fr2"), std::nullopt);  // ambiguous
}

TEST(OpenFrameSource, UnknownKindListsTheAcceptedOnes) {
  for (const std::string spec : {"kinect:0", "tum", "", "oni-file:x.oni"}) {
    auto source = OpenFrameSource(spec);
    ASSERT_FALSE(source.ok()) << spec;
    EXPECT_EQ(source.error().code, "usage") << spec;
  }
  auto unknown = OpenFrameSource("kinect:0");
  EXPECT_NE(unknown.error().message.find("unknown source 'kinect:0'"), std::string::npos);
  EXPECT_NE(unknown.error().message.find("oni:FILE, openni[:URI], tum:DIR, rgbd:DIR or clip:DIR"),
            std::string::npos);
  EXPECT_EQ(OpenFrameSource("clip:").error().code, "usage");
  EXPECT_EQ(OpenFrameSource("rgbd:").error().code, "usage");
  EXPECT_EQ(OpenFrameSource("tum:").error().code, "usage");
}

}  // namespace
}  // namespace reenact::capture
