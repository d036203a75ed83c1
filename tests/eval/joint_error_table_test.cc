// The per-joint bias / spread split of `reenact-eval tracker` against constructed runs.
#include "tests/eval/joint_error_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "synthetic/body_model.h"
#include "tests/eval/tracker_eval.h"

namespace reenact::eval {
namespace {

// A procedural-body skeleton in a given pose (world frame).
Skeleton Truth(double yaw, double twist = 0) {
  capture::BodyPose p;
  p.root_yaw = yaw;
  p.spine_twist = twist;
  p.left_arm.abduction = 0.3;
  return capture::PoseBody(p).skeleton;
}

TEST(JointErrorTable, BodyFrameIsRightForwardUp) {
  // Yaw 0: the subject faces world -y, its right is world -x, up world +z.
  const auto r = BodyFrame(Truth(0));
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->col(0).isApprox(Eigen::Vector3d(-1, 0, 0), 1e-12)) << r->col(0).transpose();
  EXPECT_TRUE(r->col(1).isApprox(Eigen::Vector3d(0, -1, 0), 1e-12)) << r->col(1).transpose();
  EXPECT_TRUE(r->col(2).isApprox(Eigen::Vector3d(0, 0, 1), 1e-12)) << r->col(2).transpose();
}

TEST(JointErrorTable, AConstantOffsetInTheBodyFrameIsAllBias) {
  // The subject turns a full circle; the tracker puts its left hand 4 cm to the subject's
  // right and 3 cm forward of the truth every frame, and every other joint exactly.
  const Eigen::Vector3d offset_body(0.04, 0.03, 0);
  JointErrorTable table;
  for (int k = 0; k < 36; ++k) {
    const Skeleton truth = Truth(2 * std::numbers::pi * k / 36);
    const Eigen::Matrix3d r = *BodyFrame(truth);
    Skeleton estimate = truth;
    estimate[Joint::kLeftHand] += r * offset_body;
    ASSERT_TRUE(table.Add(estimate, truth));
  }
  const auto stats = table.Stats();
  const JointErrorStats& hand = stats[Index(Joint::kLeftHand)];
  EXPECT_EQ(hand.frames, 36);
  EXPECT_NEAR(hand.mean_cm, 5.0, 1e-9);
  EXPECT_NEAR(hand.bias_cm.x(), 4.0, 1e-9);
  EXPECT_NEAR(hand.bias_cm.y(), 3.0, 1e-9);
  EXPECT_NEAR(hand.bias_cm.z(), 0.0, 1e-9);
  EXPECT_NEAR(hand.bias_norm_cm, 5.0, 1e-9);
  EXPECT_NEAR(hand.spread_cm, 0.0, 1e-6);
  for (int j = 0; j < kJointCount; ++j) {
    if (j == Index(Joint::kLeftHand)) continue;
    EXPECT_EQ(stats[j].frames, 36);
    EXPECT_NEAR(stats[j].mean_cm, 0, 1e-9);
    EXPECT_NEAR(stats[j].spread_cm, 0, 1e-6);
  }
}

TEST(JointErrorTable, AnOffsetFixedInTheWorldIsSpreadWhileTheBodyTurns) {
  // 5 cm along world +x while the subject turns a full circle in equal steps: in the body
  // frame the offset goes round a circle, so its mean is 0 and its spread is 5 cm.
  JointErrorTable table;
  for (int k = 0; k < 24; ++k) {
    const Skeleton truth = Truth(2 * std::numbers::pi * k / 24);
    Skeleton estimate = truth;
    estimate[Joint::kHead] += Eigen::Vector3d(0.05, 0, 0);
    table.Add(estimate, truth);
  }
  const JointErrorStats head = table.Stats()[Index(Joint::kHead)];
  EXPECT_NEAR(head.mean_cm, 5.0, 1e-9);
  EXPECT_NEAR(head.bias_norm_cm, 0.0, 1e-9);
  EXPECT_NEAR(head.spread_cm, 5.0, 1e-9);
}

TEST(JointErrorTable, BiasAndSpreadSplitTheSquaredError) {
  // Errors +1 cm and +3 cm up, alternately: bias 2 cm up, spread 1 cm.
  JointErrorTable table;
  for (int k = 0; k < 10; ++k) {
    const Skeleton truth = Truth(0.3);
    Skeleton estimate = truth;
    estimate[Joint::kWaist].z() += k % 2 ? 0.03 : 0.01;
    table.Add(estimate, truth);
  }
  const JointErrorStats waist = table.Stats()[Index(Joint::kWaist)];
  EXPECT_NEAR(waist.bias_cm.z(), 2.0, 1e-9);
  EXPECT_NEAR(waist.bias_norm_cm, 2.0, 1e-9);
  EXPECT_NEAR(waist.spread_cm, 1.0, 1e-9);
  EXPECT_NEAR(waist.mean_cm, 2.0, 1e-9);
}

TEST(JointErrorTable, UndefinedBodyFramesAndMissingJointsAreLeftOut) {
  JointErrorTable table;
  const Skeleton truth = Truth(0);
  // The neck on the waist: no up direction.
  Skeleton collapsed = truth;
  collapsed[Joint::kNeck] = collapsed[Joint::kWaist];
  EXPECT_FALSE(table.Add(truth, collapsed));
  // Shoulders and hips along the spine: no left-right direction.
  Skeleton flat = truth;
  for (Joint j : {Joint::kLeftShoulder, Joint::kRightShoulder, Joint::kLeftHip, Joint::kRightHip})
    flat[j] = truth[Joint::kWaist];
  EXPECT_FALSE(table.Add(truth, flat));
  // A missing hip in the truth.
  Skeleton no_hip = truth;
  no_hip.confidence[Index(Joint::kLeftHip)] = 0;
  EXPECT_FALSE(table.Add(truth, no_hip));
  // A missing estimate joint: that joint alone is left out.
  Skeleton estimate = truth;
  estimate.confidence[Index(Joint::kRightFoot)] = 0;
  EXPECT_TRUE(table.Add(estimate, truth));
  const auto stats = table.Stats();
  EXPECT_EQ(stats[Index(Joint::kRightFoot)].frames, 0);
  EXPECT_EQ(stats[Index(Joint::kRightFoot)].mean_cm, 0);
  EXPECT_EQ(stats[Index(Joint::kHead)].frames, 1);
  for (const JointErrorStats& s : stats) {
    EXPECT_TRUE(std::isfinite(s.spread_cm));
    EXPECT_TRUE(s.bias_cm.allFinite());
  }
}

TEST(TrackerJointsTable, ReportsOneRowPerJointWithItsColumns) {
  TrackerEvalRun run;
  TrackerJointRow row;
  row.scenario = "bvh:walk.bvh";
  row.variant = "normal";
  row.iterations = 8;
  row.subsample = 2;
  row.joint = Joint::kLeftHand;
  row.stats.frames = 36;
  row.stats.mean_cm = 5;
  row.stats.bias_cm = Eigen::Vector3d(4, 3, 0);
  row.stats.bias_norm_cm = 5;
  run.joints.push_back(row);
  const std::string json = TrackerReport(run).ToJson();
  for (const char* field : {"\"joint\": \"l_hand\"", "\"bias_x_cm\": 4", "\"bias_y_cm\": 3",
                            "\"bias_cm\": 5", "\"spread_cm\": 0", "\"mean_cm\": 5", "\"n\": 36"})
    EXPECT_NE(json.find(field), std::string::npos) << field << " in " << json;
  EXPECT_NE(TrackerReport(run).FormatTable().find("spread_cm"), std::string::npos);
}

}  // namespace
}  // namespace reenact::eval
