#include "synthetic/walk_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

constexpr double kPi = std::numbers::pi;
double Deg(double rad) { return rad * 180 / kPi; }

TEST(WalkCycle, LegsFollowTheGaitDefinition) {
  // Heel strike of the left leg (phase 0): thigh fully forward (7.5 + 17.5 = 25 degrees);
  // half a cycle later fully back (-10 degrees); the right leg is half a cycle behind.
  const BodyPose strike = WalkCyclePose(0, 1);
  EXPECT_NEAR(Deg(strike.left_leg.flexion), 25, 1e-9);
  EXPECT_NEAR(Deg(strike.right_leg.flexion), -10, 1e-9);
  const BodyPose half = WalkCyclePose(0.5, 1);
  EXPECT_NEAR(Deg(half.left_leg.flexion), -10, 1e-9);
  // Swing: the knee bends most at phase 0.72, about 60 degrees.
  double best_knee = 0, best_phase = 0;
  for (int i = 0; i < 1000; ++i) {
    const double p = i / 1000.0;
    const double knee = WalkCyclePose(p, 1).left_leg.knee;
    if (knee > best_knee) best_knee = knee, best_phase = p;
  }
  EXPECT_NEAR(best_phase, 0.72, 0.01);
  EXPECT_NEAR(Deg(best_knee), 60, 1.0);
}

TEST(WalkCycle, IsPeriodicAndSymmetric) {
  for (double p : {0.0, 0.13, 0.5, 0.77}) {
    const BodyPose a = WalkCyclePose(p, 0.8), b = WalkCyclePose(p + 1, 0.8),
                   c = WalkCyclePose(p + 0.5, 0.8);
    EXPECT_NEAR(a.left_leg.flexion, b.left_leg.flexion, 1e-12);
    EXPECT_NEAR(a.left_leg.knee, b.left_leg.knee, 1e-12);
    EXPECT_NEAR(a.left_leg.flexion, c.right_leg.flexion, 1e-12);
    EXPECT_NEAR(a.left_leg.knee, c.right_leg.knee, 1e-12);
    EXPECT_NEAR(a.left_arm.flexion, c.right_arm.flexion, 1e-12);
    // Arms swing against the legs: an arm is forward when its side's leg is back.
    EXPECT_LE(a.left_arm.flexion * (a.left_leg.flexion - 7.5 * kPi / 180 * 0.8), 1e-12);
  }
}

TEST(WalkCycle, ZeroAmplitudeStandsStill) {
  const BodyPose p = WalkCyclePose(0.3, 0);
  EXPECT_EQ(p.left_leg.flexion, 0);
  EXPECT_EQ(p.right_leg.knee, 0);
  EXPECT_EQ(p.left_arm.flexion, 0);
  EXPECT_EQ(p.spine_twist, 0);
}

TEST(CircleWalk, WalksOneFullCircleFromTheOrigin) {
  CircleWalkOptions o;
  const auto poses = CircleWalk(o, 30);
  ASSERT_EQ(poses.size(), 210u);
  EXPECT_EQ(poses.front().root_xy, Eigen::Vector2d::Zero());
  EXPECT_EQ(poses.front().root_yaw, 0);
  const Eigen::Vector2d centre(o.radius_m, 0);
  double max_step = 0;
  for (size_t k = 0; k < poses.size(); ++k) {
    EXPECT_NEAR((poses[k].root_xy - centre).norm(), o.radius_m, 1e-12);
    // Facing along the tangent: the heading is the angle walked around the centre.
    const Eigen::Vector2d facing(std::sin(poses[k].root_yaw), -std::cos(poses[k].root_yaw));
    const Eigen::Vector2d radial = (poses[k].root_xy - centre).normalized();
    EXPECT_NEAR(facing.dot(radial), 0, 1e-12);
    if (k > 0) max_step = std::max(max_step, (poses[k].root_xy - poses[k - 1].root_xy).norm());
  }
  // The last frame is 1/30 s before the end: within a hair of a full circle.
  EXPECT_NEAR(poses.back().root_yaw, 2 * kPi, 1e-3);
  // Top speed 2 pi 0.8 m / (7 - 0.8) s = 0.81 m/s, a slow walk.
  EXPECT_NEAR(max_step * 30, 2 * kPi * o.radius_m / (o.duration_s - o.ramp_s), 0.01);
  // It starts and ends standing (amplitude 0), mid-walk the legs swing fully.
  EXPECT_NEAR(poses.front().left_leg.flexion, 0, 1e-12);
  EXPECT_NEAR(poses.front().left_arm.flexion, 0, 1e-12);
  double range = 0;
  for (int k = 60; k < 120; ++k)
    range = std::max(range, std::abs(poses[k].left_leg.flexion - poses[k - 15].left_leg.flexion));
  EXPECT_GT(Deg(range), 25);
}

TEST(CircleWalk, BadOptionsThrow) {
  CircleWalkOptions o;
  o.duration_s = 1.0;  // shorter than the two ramps
  EXPECT_THROW(CircleWalk(o, 30), CheckError);
  EXPECT_THROW(CircleWalk(CircleWalkOptions{}, 0), CheckError);
  o = CircleWalkOptions{};
  o.radius_m = 0;
  EXPECT_THROW(CircleWalk(o, 30), CheckError);
}

}  // namespace
}  // namespace reenact::capture
