// Agreement figures on constructed poses whose answers follow from the construction: moving
// joints, the mean-pose baseline, PCK, tracked share, first estimate, means over sequences,
// constant body-frame offsets fitted on other subjects and turned with the body, and
// sequences without any estimate (no NaN).
#include "tests/eval/reference_agreement.h"

#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "tests/eval/joint_error_table.h"

namespace reenact::eval {
namespace {

// A person standing 2.5 m in front of the sensor (OpenCV sensor frame: x right, y down, z
// forward), facing it, turned by yaw_rad about the vertical through the waist, shifted by
// `shift`.
Skeleton Standing(double yaw_rad = 0, const Eigen::Vector3d& shift = Eigen::Vector3d::Zero()) {
  // Body coordinates: x the person's left (the sensor's right when facing it), y down, z
  // away from the sensor (the person faces -z).
  const std::array<Eigen::Vector3d, kJointCount> body = {
      Eigen::Vector3d(0, -0.75, 0),      Eigen::Vector3d(0, -0.50, 0),
      Eigen::Vector3d(0, -0.25, 0),      Eigen::Vector3d(0, 0, 0),
      Eigen::Vector3d(0.20, -0.45, 0),   Eigen::Vector3d(0.25, -0.20, 0.02),
      Eigen::Vector3d(0.27, 0.05, -0.05), Eigen::Vector3d(-0.20, -0.45, 0),
      Eigen::Vector3d(-0.25, -0.20, 0.02), Eigen::Vector3d(-0.27, 0.05, -0.05),
      Eigen::Vector3d(0.10, 0.05, 0),    Eigen::Vector3d(0.11, 0.45, -0.02),
      Eigen::Vector3d(0.11, 0.85, 0.03), Eigen::Vector3d(-0.10, 0.05, 0),
      Eigen::Vector3d(-0.11, 0.45, -0.02), Eigen::Vector3d(-0.11, 0.85, 0.03)};
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitY()).matrix();
  Skeleton s;
  for (int j = 0; j < kJointCount; ++j)
    s.Set(static_cast<Joint>(j), Eigen::Vector3d(0, 0.2, 2.5) + shift + turn * body[j]);
  return s;
}

// The constant per-joint offsets (metres, body frame) of a reference tracker against ours.
std::array<Eigen::Vector3d, kJointCount> BodyOffsets() {
  std::array<Eigen::Vector3d, kJointCount> c;
  for (int j = 0; j < kJointCount; ++j)
    c[j] = Eigen::Vector3d(0.01 * (j % 5) - 0.02, 0.04 - 0.01 * (j % 3), 0.03 * ((j % 4) - 1.5));
  return c;
}

// The reference that sees `estimate` with the offsets in the estimate's body frame.
Skeleton ReferenceOf(const Skeleton& estimate) {
  const auto frame = BodyFrame(estimate);
  EXPECT_TRUE(frame.has_value());
  const auto c = BodyOffsets();
  Skeleton r = estimate;
  for (int j = 0; j < kJointCount; ++j) r.position[j] += *frame * c[j];
  return r;
}

double MaxJointError(const Skeleton& a, const Skeleton& b) {
  double worst = 0;
  for (int j = 0; j < kJointCount; ++j)
    worst = std::max(worst, (a.position[j] - b.position[j]).norm());
  return worst;
}

JointPoints Points(std::initializer_list<Eigen::Vector3d> points) {
  JointPoints p;
  for (const auto& x : points) p.emplace_back(x);
  return p;
}

TEST(ReferenceAgreement, BodyOffsetFittedOnOtherSubjectsIsRemovedFromTheTestSubject) {
  // Three other subjects, each facing another way and standing elsewhere, with the same
  // body-frame offsets; the test subject faces yet another way.
  JointOffsetFit fit;
  for (int subject = 0; subject < 3; ++subject) {
    JointOffsetFit own;
    for (int f = 0; f < 5; ++f) {
      const Skeleton estimate =
          Standing(0.3 * subject - 0.4 + 0.05 * f, Eigen::Vector3d(0.1 * subject, 0, 0.05 * f));
      own.Add(estimate, ReferenceOf(estimate));
    }
    fit.Merge(own);
  }
  EXPECT_EQ(fit.frames(), 15);
  const JointOffsets offsets = fit.Offsets();
  for (int j = 0; j < kJointCount; ++j)
    EXPECT_LT((offsets.in_body[j] - BodyOffsets()[j]).norm(), 1e-12) << j;
  const Skeleton estimate = Standing(1.1, Eigen::Vector3d(-0.3, 0, 0.4));
  const Skeleton reference = ReferenceOf(estimate);
  EXPECT_GT(MaxJointError(estimate, reference), 0.03);  // the offsets are there
  EXPECT_LT(MaxJointError(offsets.Apply(estimate), reference), 1e-12);
}

TEST(ReferenceAgreement, OffsetTurnsWithTheBody) {
  // Fitted on a person facing the sensor; applied to the person turned a quarter: the
  // corrected joints follow the turned reference, where the same offsets taken in the sensor
  // frame would leave |c - R c| per joint.
  JointOffsetFit fit;
  const Skeleton facing = Standing();
  fit.Add(facing, ReferenceOf(facing));
  const JointOffsets offsets = fit.Offsets();
  const Skeleton turned = Standing(M_PI / 2);
  const Skeleton reference = ReferenceOf(turned);
  EXPECT_LT(MaxJointError(offsets.Apply(turned), reference), 1e-12);
  Skeleton sensor_frame_offsets = turned;
  for (int j = 0; j < kJointCount; ++j) sensor_frame_offsets.position[j] += offsets.in_sensor[j];
  EXPECT_GT(MaxJointError(sensor_frame_offsets, reference), 0.02);
}

TEST(ReferenceAgreement, DegenerateBodyFrameFallsBackToTheSensorFrameOffset) {
  JointOffsetFit fit;
  const Eigen::Vector3d d(0.01, -0.02, 0.03);
  for (int f = 0; f < 3; ++f) {
    const Skeleton estimate = Standing(0.2 * f);
    Skeleton reference = estimate;
    for (auto& p : reference.position) p += d;
    fit.Add(estimate, reference);
  }
  Skeleton flat = Standing(0.5);  // the hips missing: no body frame
  flat.confidence[Index(Joint::kLeftHip)] = 0;
  flat.confidence[Index(Joint::kRightHip)] = 0;
  ASSERT_FALSE(BodyFrame(flat).has_value());
  const Skeleton corrected = fit.Offsets().Apply(flat);
  for (Joint j : {Joint::kHead, Joint::kLeftHand, Joint::kRightFoot})
    EXPECT_LT((corrected[j] - (flat[j] + d)).norm(), 1e-12);
  EXPECT_FALSE(corrected.Has(Joint::kLeftHip));
  EXPECT_EQ(corrected[Joint::kLeftHip], flat[Joint::kLeftHip]);
}

TEST(ReferenceAgreement, NoFramesGiveZeroOffsets) {
  const Skeleton s = Standing(0.3);
  EXPECT_EQ(MaxJointError(JointOffsetFit().Offsets().Apply(s), s), 0);
}

TEST(ReferenceAgreement, MovingJointsAreThoseFartherThanTenCmFromTheirMean) {
  // Joint 0 still, joint 1 swinging +-9 cm (not moving), joint 2 +-11 cm (moving), joint 3
  // stepping 15 cm once (7.5 cm from its mean on every frame: not moving, although its
  // positions lie 15 cm apart), joint 4 only on one frame.
  std::vector<std::optional<JointPoints>> reference;
  for (int f = 0; f < 4; ++f) {
    const double s = f % 2 ? 1 : -1;
    JointPoints p = Points({Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0.09 * s, 0, 2),
                            Eigen::Vector3d(0, 0.11 * s, 2), Eigen::Vector3d(0, 0, f < 2 ? 2 : 2.15)});
    p.emplace_back(f == 0 ? std::optional(Eigen::Vector3d(1, 1, 1)) : std::nullopt);
    reference.push_back(p);
  }
  reference.push_back(std::nullopt);  // a frame without a reference
  EXPECT_EQ(MovingJoints(reference), (std::vector<bool>{false, false, true, false, false}));
  EXPECT_EQ(MovingJoints(reference, 0.05), (std::vector<bool>{false, true, true, true, false}));
  EXPECT_TRUE(MovingJoints({}).empty());
}

TEST(ReferenceAgreement, BaselinePlacesTheMeanPoseAtTheCentre) {
  // The centre (joint 0) walks; joint 1 keeps 20 cm above it (error 0); joint 2 lies 20 cm
  // or 40 cm to its side (mean 30 cm: 10 cm off on every frame).
  std::vector<std::optional<JointPoints>> reference;
  for (int f = 0; f < 4; ++f) {
    const Eigen::Vector3d c(0.1 * f, 0, 2);
    reference.push_back(Points({c, c + Eigen::Vector3d(0, -0.2, 0),
                                c + Eigen::Vector3d(f % 2 ? 0.4 : 0.2, 0, 0)}));
  }
  const auto baseline = MeanPoseAtCentre(reference, 0);
  ASSERT_EQ(baseline.size(), 4u);
  for (int f = 0; f < 4; ++f) {
    ASSERT_TRUE(baseline[f].has_value());
    EXPECT_LT((*(*baseline[f])[1] - *(*reference[f])[1]).norm(), 1e-12);
    EXPECT_NEAR((*(*baseline[f])[2] - *(*reference[f])[2]).norm(), 0.1, 1e-12);
  }
  const SequenceAgreement s = CompareSequence(baseline, reference, MovingJoints(reference));
  ASSERT_TRUE(s.mpjpe_cm && s.moving_mpjpe_cm);
  EXPECT_NEAR(*s.mpjpe_cm, 10.0 / 3, 1e-9);  // (0 + 0 + 10) / 3 joints
  // Moving: the centre (15 cm from its mean at the ends), joint 1 alike, and joint 2.
  EXPECT_EQ(s.moving_joints, 3);
  EXPECT_NEAR(*s.moving_mpjpe_cm, 10.0 / 3, 1e-9);
  // A frame without its centre gets no baseline.
  reference[2]->at(0).reset();
  EXPECT_FALSE(MeanPoseAtCentre(reference, 0)[2].has_value());
}

TEST(ReferenceAgreement, MpjpeAveragesFramesAndMovingJointsOnly) {
  // Two joints, joint 1 moving. Frame 0: errors 2 and 4 cm; frame 1: 6 and 0 cm; frame 2:
  // joint 1 not estimated, joint 0 off by 10 cm.
  const Eigen::Vector3d a(0, 0, 2), b(0.5, 0, 2);
  const std::vector<std::optional<JointPoints>> reference = {Points({a, b}), Points({a, b}),
                                                             Points({a, b})};
  JointPoints last = Points({a + Eigen::Vector3d(0.10, 0, 0)});
  last.emplace_back();
  const std::vector<std::optional<JointPoints>> estimate = {
      Points({a + Eigen::Vector3d(0.02, 0, 0), b + Eigen::Vector3d(0, 0.04, 0)}),
      Points({a + Eigen::Vector3d(0, 0, 0.06), b}), last};
  const SequenceAgreement s =
      CompareSequence(estimate, reference, {false, true}, AgreementOptions{.min_travel_m = 0.1,
                                                                           .pck_m = 0.05,
                                                                           .warmup_frames = 0});
  ASSERT_TRUE(s.mpjpe_cm && s.moving_mpjpe_cm && s.pck && s.joint_share);
  EXPECT_NEAR(*s.mpjpe_cm, (3 + 3 + 10) / 3.0, 1e-9);
  EXPECT_NEAR(*s.moving_mpjpe_cm, (4 + 0) / 2.0, 1e-9);  // frame 2 has no moving estimate
  EXPECT_NEAR(*s.pck, 3.0 / 5, 1e-12);                   // 2, 4, 0 cm within 5; 6, 10 not
  EXPECT_NEAR(*s.joint_share, 5.0 / 6, 1e-12);
  ASSERT_EQ(s.frame_error_cm.size(), 3u);
  EXPECT_NEAR(*s.frame_error_cm[2], 10, 1e-9);
}

TEST(ReferenceAgreement, PckCountsEstimatesWithinTenCm) {
  const Eigen::Vector3d r(0, 0, 2);
  const JointPoints reference = Points({r, r, r, r});
  const JointPoints estimate =
      Points({r + Eigen::Vector3d(0.05, 0, 0), r + Eigen::Vector3d(0, 0.099, 0),
              r + Eigen::Vector3d(0, 0, 0.101), r + Eigen::Vector3d(0.08, 0.08, 0)});
  const FrameAgreement a = CompareFrame(estimate, reference, {});
  EXPECT_EQ(a.compared, 4);
  EXPECT_EQ(a.within, 2);  // 5 cm and 9.9 cm; 10.1 cm and 11.3 cm are not
  EXPECT_FALSE(a.MovingMeanM().has_value());
}

TEST(ReferenceAgreement, TrackedShareCountsFramesAfterTheFirstSecond) {
  // 60 frames at 30 fps; the tracker starts on frame 10 and loses frames 40-44: of the 30
  // frames after the first second, 25 have a skeleton.
  std::vector<std::optional<JointPoints>> reference, estimate;
  for (int f = 0; f < 60; ++f) {
    reference.push_back(PointsOf(Standing()));
    estimate.push_back(f >= 10 && (f < 40 || f > 44) ? std::optional(PointsOf(Standing()))
                                                     : std::nullopt);
  }
  const SequenceAgreement s = CompareSequence(estimate, reference, MovingJoints(reference));
  EXPECT_EQ(s.frames, 60);
  EXPECT_EQ(s.tracked, 45);
  EXPECT_EQ(s.warm_frames, 30);
  EXPECT_EQ(s.warm_tracked, 25);
  ASSERT_TRUE(s.tracked_share && s.first_estimate);
  EXPECT_NEAR(*s.tracked_share, 25.0 / 30, 1e-12);
  EXPECT_EQ(*s.first_estimate, 10);
  EXPECT_EQ(s.moving_joints, 0);
  EXPECT_FALSE(s.moving_mpjpe_cm.has_value());
  EXPECT_NEAR(*s.mpjpe_cm, 0, 1e-12);
}

TEST(ReferenceAgreement, SequenceWithoutEstimatesHasNoFiguresAndNoNan) {
  std::vector<std::optional<JointPoints>> reference(40, PointsOf(Standing()));
  const std::vector<std::optional<JointPoints>> estimate(40);
  const SequenceAgreement s = CompareSequence(estimate, reference, MovingJoints(reference));
  EXPECT_EQ(s.tracked, 0);
  EXPECT_FALSE(s.first_estimate || s.mpjpe_cm || s.moving_mpjpe_cm || s.pck || s.joint_share);
  ASSERT_TRUE(s.tracked_share.has_value());
  EXPECT_EQ(*s.tracked_share, 0);
  const GroupAgreement g = Aggregate({&s, &s});
  EXPECT_EQ(g.sequences, 2);
  EXPECT_EQ(g.untracked_sequences, 2);
  EXPECT_FALSE(g.first_estimate_median || g.mpjpe_cm || g.moving_mpjpe_cm || g.pck ||
               g.joint_share);
  EXPECT_EQ(*g.tracked_share, 0);
  const GroupAgreement empty = Aggregate({});
  EXPECT_FALSE(empty.tracked_share || empty.mpjpe_cm);
}

TEST(ReferenceAgreement, AggregateWeighsSequencesAlikeAndPoolsTheTrackedShare) {
  // A 40-frame sequence 1 cm off tracked from frame 0, a 100-frame one 3 cm off tracked from
  // frame 50, and one never tracked.
  const auto sequence = [](int frames, int start, double off_m) {
    std::vector<std::optional<JointPoints>> reference, estimate;
    for (int f = 0; f < frames; ++f) {
      const Skeleton s = Standing();
      reference.push_back(PointsOf(s));
      Skeleton e = s;
      for (auto& p : e.position) p.x() += off_m;
      estimate.push_back(f >= start ? std::optional(PointsOf(e)) : std::nullopt);
    }
    return CompareSequence(estimate, reference, MovingJoints(reference));
  };
  const SequenceAgreement a = sequence(40, 0, 0.01), b = sequence(100, 50, 0.03),
                          c = sequence(40, 40, 0);
  const GroupAgreement g = Aggregate({&a, &b, &c});
  EXPECT_EQ(g.sequences, 3);
  EXPECT_EQ(g.frames, 180);
  EXPECT_EQ(g.untracked_sequences, 1);
  ASSERT_TRUE(g.mpjpe_cm && g.tracked_share && g.first_estimate_median && g.pck);
  EXPECT_NEAR(*g.mpjpe_cm, 2, 1e-9);  // (1 + 3) / 2, not weighted by frames
  EXPECT_NEAR(*g.tracked_share, (10.0 + 50) / (10 + 70 + 10), 1e-12);
  EXPECT_NEAR(*g.first_estimate_median, 25, 1e-12);  // frames 0 and 50
  EXPECT_NEAR(*g.pck, 1, 1e-12);
}

}  // namespace
}  // namespace reenact::eval
