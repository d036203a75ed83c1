// Retargeting a skeleton onto the procedural body (body_pose_from_skeleton.h): round trips
// through PoseBody, bvh: motion played on the procedural body, degenerate input.
#include "synthetic/body_pose_from_skeleton.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>

#include "synthetic/room.h"
#include "synthetic/scenario.h"
#include "synthetic/sensor_placement.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

double MaxJointError(const Skeleton& a, const Skeleton& b) {
  double worst = 0;
  for (int j = 0; j < kJointCount; ++j)
    worst = std::max(worst, (a.position[j] - b.position[j]).norm());
  return worst;
}

bool Finite(const BodyPose& p) {
  bool ok = p.root_xy.allFinite() && std::isfinite(p.root_yaw) && std::isfinite(p.spine_bend) &&
            std::isfinite(p.spine_twist) && std::isfinite(p.head_pitch);
  for (const ArmPose* a : {&p.left_arm, &p.right_arm})
    ok = ok && std::isfinite(a->abduction) && std::isfinite(a->flexion) && std::isfinite(a->elbow);
  for (const LegPose* l : {&p.left_leg, &p.right_leg})
    ok = ok && std::isfinite(l->abduction) && std::isfinite(l->flexion) && std::isfinite(l->knee) &&
         std::isfinite(l->ankle) && std::isfinite(l->ankle_roll);
  return ok;
}

// Every angle inside the limits (small slack for the projected steps' rounding).
void ExpectWithinLimits(const BodyPose& p, const BodyPoseLimits& l = {}) {
  constexpr double e = 1e-12;
  EXPECT_TRUE(Finite(p));
  EXPECT_GT(p.root_yaw, -kPi - e);
  EXPECT_LE(p.root_yaw, kPi + e);
  EXPECT_GE(p.spine_bend, l.spine_bend_min - e);
  EXPECT_LE(p.spine_bend, l.spine_bend_max + e);
  EXPECT_LE(std::abs(p.spine_twist), l.spine_twist_max + e);
  EXPECT_LE(std::abs(p.head_pitch), l.head_pitch_max + e);
  for (const ArmPose* a : {&p.left_arm, &p.right_arm}) {
    EXPECT_GE(a->abduction, l.arm_abduction_min - e);
    EXPECT_LE(a->abduction, l.arm_abduction_max + e);
    EXPECT_GE(a->flexion, l.arm_flexion_min - e);
    EXPECT_LE(a->flexion, l.arm_flexion_max + e);
    EXPECT_GE(a->elbow, -e);
    EXPECT_LE(a->elbow, l.elbow_max + e);
  }
  for (const LegPose* g : {&p.left_leg, &p.right_leg}) {
    EXPECT_GE(g->abduction, l.leg_abduction_min - e);
    EXPECT_LE(g->abduction, l.leg_abduction_max + e);
    EXPECT_GE(g->flexion, l.leg_flexion_min - e);
    EXPECT_LE(g->flexion, l.leg_flexion_max + e);
    EXPECT_GE(g->knee, -e);
    EXPECT_LE(g->knee, l.knee_max + e);
    EXPECT_GE(g->ankle, l.ankle_min - e);
    EXPECT_LE(g->ankle, l.ankle_max + e);
    EXPECT_LE(std::abs(g->ankle_roll), l.ankle_roll_max + e);
  }
}

BodyPose RandomPose(std::mt19937_64& rng, const BodyPoseLimits& l) {
  const auto u = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  BodyPose p;
  p.root_xy = Eigen::Vector2d(u(-2, 2), u(-2, 2));
  p.root_yaw = u(-kPi, kPi);
  p.spine_bend = u(l.spine_bend_min, l.spine_bend_max);
  p.spine_twist = u(-l.spine_twist_max, l.spine_twist_max);
  p.head_pitch = u(-l.head_pitch_max, l.head_pitch_max);
  for (ArmPose* a : {&p.left_arm, &p.right_arm}) {
    a->abduction = u(l.arm_abduction_min, l.arm_abduction_max);
    a->flexion = u(l.arm_flexion_min, l.arm_flexion_max);
    a->elbow = u(0, l.elbow_max);
  }
  for (LegPose* g : {&p.left_leg, &p.right_leg}) {
    g->abduction = u(l.leg_abduction_min, l.leg_abduction_max);
    g->flexion = u(l.leg_flexion_min, l.leg_flexion_max);
    g->knee = u(0, l.knee_max);
  }
  return p;
}

// The limbs' frames, bones and joints are exact functions of the angles, and the solver stops
// at a direction residual near 1e-12 (squared cost 1e-24 or a step below 1e-13 rad), so every
// joint, at most 1.3 m from the waist along the chain, lands within 1e-6 m (a generous
// margin over 1.3 m * 1e-9 rad for the numeric Jacobian's rounding).
constexpr double kRoundTripM = 1e-6;

TEST(BodyPoseFromSkeleton, RandomPosesWithinTheLimitsRoundTrip) {
  std::mt19937_64 rng(7);
  const BodyPoseLimits limits;
  for (int k = 0; k < 400; ++k) {
    const BodyPose truth = RandomPose(rng, limits);
    const Skeleton target = PoseBody(truth).skeleton;
    const BodyPoseFit fit = BodyPoseFromSkeleton(target);
    EXPECT_EQ(fit.bones_used, 13);
    EXPECT_EQ(fit.yaw_from, "hips");
    EXPECT_LT(fit.rms_direction_error, 1e-8) << k;
    EXPECT_LT(MaxJointError(PoseBody(fit.pose).skeleton, target), kRoundTripM) << k;
    ExpectWithinLimits(fit.pose);
    // The pose's own, observable angles come back.
    EXPECT_NEAR(fit.pose.root_yaw, truth.root_yaw, 1e-9);
    EXPECT_NEAR(fit.pose.spine_bend, truth.spine_bend, 1e-6);
    EXPECT_NEAR(fit.pose.spine_twist, truth.spine_twist, 1e-6);
    EXPECT_NEAR(fit.pose.head_pitch, truth.head_pitch, 1e-6);
    EXPECT_NEAR((fit.pose.root_xy - truth.root_xy).norm(), 0, 1e-12);
    if (HasFailure()) break;
  }
}

TEST(BodyPoseFromSkeleton, ScenarioMotionsRoundTrip) {
  for (const char* name : {"turn-and-kick", "raise-and-crouch", "walk-handheld"}) {
    const Scenario s = MakeScenario(name).value();
    for (size_t f = 0; f < s.poses.size(); ++f) {
      const Skeleton target = PoseBody(s.poses[f]).skeleton;
      const BodyPoseFit fit = BodyPoseFromSkeleton(target);
      EXPECT_LT(MaxJointError(PoseBody(fit.pose).skeleton, target), kRoundTripM)
          << name << " frame " << f;
      ExpectWithinLimits(fit.pose);
    }
  }
}

TEST(BodyPoseFromSkeleton, OtherProportionsTransferDirectionsOnly) {
  // A taller subject with longer limbs (same head offset): the bone directions are
  // reproduced exactly, the joints follow the procedural body's own lengths.
  BodyDimensions tall;
  tall.thigh = 0.5;
  tall.shin = 0.47;
  tall.upper_arm = 0.33;
  tall.forearm = 0.29;
  tall.lower_spine = 0.26;
  tall.shoulder_half_width = 0.21;
  std::mt19937_64 rng(3);
  for (int k = 0; k < 50; ++k) {
    const Skeleton target = PoseBody(RandomPose(rng, {}), tall).skeleton;
    const BodyPoseFit fit = BodyPoseFromSkeleton(target);
    EXPECT_LT(fit.rms_direction_error, 1e-8) << k;
    const Skeleton mine = PoseBody(fit.pose).skeleton;
    const BodyDimensions d;
    EXPECT_NEAR((mine[Joint::kLeftKnee] - mine[Joint::kLeftHip]).norm(), d.thigh, 1e-9);
    EXPECT_NEAR(mine[Joint::kWaist].x(), target[Joint::kWaist].x(), 1e-12);
  }
}

TEST(BodyPoseFromSkeleton, FeetAreKeptLevel) {
  // A walking pose: the sole's forward and left axes lie horizontal.
  BodyPose p;
  p.root_yaw = 0.4;
  p.left_leg.flexion = 0.5;
  p.left_leg.knee = 0.9;
  p.left_leg.abduction = 0.1;
  p.right_leg.flexion = -0.2;
  const BodyPoseFit fit = BodyPoseFromSkeleton(PoseBody(p).skeleton);
  const PosedBody posed = PoseBody(fit.pose);
  for (Segment foot : {Segment::kLeftFoot, Segment::kRightFoot}) {
    const Eigen::Matrix3d r = posed.world_from_segment[static_cast<int>(foot)].linear();
    EXPECT_NEAR(r(2, 0), 0, 1e-9);
    EXPECT_NEAR(r(2, 1), 0, 1e-9);
    EXPECT_GT(r(2, 2), 0.99);  // sole down
  }
}

TEST(BodyPoseFromSkeleton, AMissingSkeletonGivesTheRestPose) {
  const BodyPoseFit fit = BodyPoseFromSkeleton(Skeleton{});
  EXPECT_EQ(fit.bones_used, 0);
  EXPECT_EQ(fit.yaw_from, "none");
  EXPECT_EQ(fit.rms_direction_error, 0);
  const Skeleton rest = PoseBody(BodyPose{}).skeleton;
  EXPECT_LT(MaxJointError(PoseBody(fit.pose).skeleton, rest), 1e-12);
}

TEST(BodyPoseFromSkeleton, ZeroLengthBonesCarryNoDirection) {
  // Every joint at one point (present): no bone, the rest pose, placed at that point.
  Skeleton s;
  for (int j = 0; j < kJointCount; ++j) s.Set(static_cast<Joint>(j), Eigen::Vector3d(1, 2, 0.5));
  const BodyPoseFit fit = BodyPoseFromSkeleton(s);
  EXPECT_EQ(fit.bones_used, 0);
  EXPECT_EQ(fit.yaw_from, "none");
  ExpectWithinLimits(fit.pose);
  EXPECT_EQ(fit.pose.root_xy, Eigen::Vector2d(1, 2));
  EXPECT_EQ(fit.pose.left_arm.elbow, 0);
  EXPECT_EQ(fit.pose.spine_bend, 0);
}

TEST(BodyPoseFromSkeleton, NonFiniteAndMissingJointsAreLeftOut) {
  BodyPose truth;
  truth.root_yaw = 1.0;
  truth.left_arm = {0.8, 0.3, 0.9};
  truth.right_leg = {0.6, 0.1, 0.7, 0, 0};
  Skeleton s = PoseBody(truth).skeleton;
  // The left hand missing: the upper arm still comes back exactly, the elbow stays at rest.
  s.confidence[Index(Joint::kLeftHand)] = 0;
  // A NaN right elbow with full confidence: that arm's two bones are unusable.
  s[Joint::kRightElbow] = Eigen::Vector3d(NAN, 0, 0);
  const BodyPoseFit fit = BodyPoseFromSkeleton(s);
  EXPECT_EQ(fit.bones_used, 10);
  ExpectWithinLimits(fit.pose);
  const Skeleton mine = PoseBody(fit.pose).skeleton;
  EXPECT_LT((mine[Joint::kLeftElbow] - s[Joint::kLeftElbow]).norm(), kRoundTripM);
  EXPECT_EQ(fit.pose.left_arm.elbow, 0);
  EXPECT_EQ(fit.pose.right_arm.abduction, 0);
  EXPECT_EQ(fit.pose.right_arm.flexion, 0);
  EXPECT_LT((mine[Joint::kRightFoot] - s[Joint::kRightFoot]).norm(), kRoundTripM);
}

TEST(BodyPoseFromSkeleton, VerticalLinesFallBack) {
  BodyPose truth;
  truth.root_yaw = -0.7;
  const Skeleton upright = PoseBody(truth).skeleton;
  // The hips one above the other: the yaw comes from the shoulders.
  Skeleton s = upright;
  s[Joint::kLeftHip] = s[Joint::kRightHip] + Eigen::Vector3d(0, 0, 0.18);
  BodyPoseFit fit = BodyPoseFromSkeleton(s);
  EXPECT_EQ(fit.yaw_from, "shoulders");
  EXPECT_NEAR(fit.pose.root_yaw, -0.7, 1e-9);
  ExpectWithinLimits(fit.pose);
  // The shoulders too: no facing at all, yaw 0, still a defined pose.
  s[Joint::kLeftShoulder] = s[Joint::kRightShoulder] + Eigen::Vector3d(0, 0, 0.37);
  fit = BodyPoseFromSkeleton(s);
  EXPECT_EQ(fit.yaw_from, "none");
  EXPECT_EQ(fit.pose.root_yaw, 0);
  ExpectWithinLimits(fit.pose);
}

TEST(BodyPoseFromSkeleton, ParallelAndUnreachableBonesStayWithinTheLimits) {
  BodyPose truth;
  Skeleton s = PoseBody(truth).skeleton;
  // A forearm folded straight back onto the upper arm (180 degrees, past the elbow's range),
  // an arm straight up (its abduction undetermined), a shin pointing forward and up.
  s[Joint::kLeftHand] = s[Joint::kLeftShoulder];
  s[Joint::kRightElbow] = s[Joint::kRightShoulder] + Eigen::Vector3d(0, 0, 0.29);
  s[Joint::kRightHand] = s[Joint::kRightElbow] + Eigen::Vector3d(0, 0, 0.32);
  s[Joint::kLeftFoot] = s[Joint::kLeftKnee] + Eigen::Vector3d(0, -0.3, 0.2);
  const BodyPoseFit fit = BodyPoseFromSkeleton(s);
  ExpectWithinLimits(fit.pose);
  EXPECT_NEAR(fit.pose.left_arm.elbow, BodyPoseLimits{}.elbow_max, 1e-9);
  // The right arm points up to within the flexion / abduction limits' reach.
  const Skeleton mine = PoseBody(fit.pose).skeleton;
  const Eigen::Vector3d up = (mine[Joint::kRightHand] - mine[Joint::kRightShoulder]).normalized();
  EXPECT_GT(up.z(), std::cos(0.05));
}

TEST(BodyPoseFromSkeleton, ArbitraryPointsGiveADefinedPose) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 200; ++k) {
    Skeleton s;
    for (int j = 0; j < kJointCount; ++j)
      if (u(rng) > -0.6) s.Set(static_cast<Joint>(j), Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const BodyPoseFit fit = BodyPoseFromSkeleton(s);
    ExpectWithinLimits(fit.pose);
    EXPECT_TRUE(std::isfinite(fit.rms_direction_error));
    EXPECT_LE(fit.rms_direction_error, 2.0 + 1e-12);  // |a - b| <= 2 for unit vectors
    if (HasFailure()) break;
  }
}

TEST(BodyPoseFromSkeleton, BadOptionsAreRefused) {
  BodyPoseFromSkeletonOptions o;
  o.iterations = -1;
  EXPECT_ANY_THROW(BodyPoseFromSkeleton(Skeleton{}, o));
  o = {};
  o.limits.knee_max = -0.1;
  EXPECT_ANY_THROW(BodyPoseFromSkeleton(Skeleton{}, o));
  o = {};
  o.limits.arm_flexion_min = NAN;
  EXPECT_ANY_THROW(BodyPoseFromSkeleton(Skeleton{}, o));
}

std::string CmuWalk() {
  return (fs::path(REENACT_SHARED_DATA_DIR) / "mocap" / "cmu-131_01-walk.bvh").string();
}

TEST(BvhOnTheProceduralBody, TheCmuWalkPlays) {
  const std::string path = CmuWalk();
  if (!fs::exists(path)) GTEST_SKIP() << path << " not present";
  const Scenario scenario = MakeScenario("bvh:" + path).value();
  const Expected<SyntheticScene> made = SyntheticScene::Create("bvh:" + path);
  ASSERT_TRUE(made.ok()) << made.error().message;
  const SyntheticScene& scene = *made;
  ASSERT_EQ(scene.frame_count(), scenario.frame_count());
  const Skeleton first = scene.skeleton_in_world(0);
  const BodyDimensions d;
  for (int f = 0; f < scene.frame_count(); ++f) {
    const Skeleton s = scene.skeleton_in_world(f);
    const Skeleton& target = scenario.target_skeletons[f];
    // Stands on the floor: the lower ankle at the body's ankle height.
    EXPECT_NEAR(std::min(s[Joint::kLeftFoot].z(), s[Joint::kRightFoot].z()), d.ankle_height, 1e-9)
        << f;
    // Walks where the motion walks: the waist above the target's.
    EXPECT_LT((s[Joint::kWaist] - target[Joint::kWaist]).head<2>().norm(), 1e-12) << f;
    // Keeps its own bone lengths.
    for (int p = 0; p < kBodyPartCount; ++p) {
      const auto [a, b] = PartJoints(static_cast<BodyPart>(p));
      EXPECT_NEAR((s[a] - s[b]).norm(), (first[a] - first[b]).norm(), 1e-9) << f;
    }
    // Faces the way the motion faces: the hip lines' horizontal parts agree (the yaw comes
    // from them exactly).
    const Eigen::Vector2d h = (s[Joint::kLeftHip] - s[Joint::kRightHip]).head<2>();
    const Eigen::Vector2d ht = (target[Joint::kLeftHip] - target[Joint::kRightHip]).head<2>();
    EXPECT_GT(h.normalized().dot(ht.normalized()), 1 - 1e-12) << f;
    // The procedural body (1.75 m) stays in the sensor's view placed for the motion, with
    // the placement's own margins less the flesh radius (it is taller than the subject).
    StaticSensorOptions loose;
    loose.body_radius_m = 0.05;
    EXPECT_TRUE(SensorSeesSkeleton(s, scene.sensor_camera(), scene.world_from_sensor(f),
                                   *SharedRoom(), loose))
        << f;
    if (HasFailure()) break;
  }
  // Frames render with the subject in view.
  for (int f : {0, scene.frame_count() / 2, scene.frame_count() - 1}) {
    const SyntheticView view = scene.RenderSensor(f);
    int subject = 0;
    for (uint8_t m : view.mask.data) subject += m == 255;
    EXPECT_GT(subject, 2000) << f;
  }
}

// Sum of squared unit-direction differences over the given bones.
double DirectionCost(const Skeleton& fitted, const Skeleton& target,
                     std::initializer_list<std::pair<Joint, Joint>> bones) {
  double sum = 0;
  for (const auto& [a, b] : bones)
    sum +=
        ((fitted[b] - fitted[a]).normalized() - (target[b] - target[a]).normalized()).squaredNorm();
  return sum;
}

TEST(BvhOnTheProceduralBody, EachStageIsALeastSquaresOptimumOnTheCmuMotion) {
  // CMU 131_01 is a stylised walk with a spin and a squat; the procedural body cannot tilt
  // its pelvis, lean sideways or turn an upper arm about its axis, so the fit is not exact.
  // What the method promises is each stage's least-squares optimum: no small change of one
  // of its angles (within the limits) lowers that stage's direction error.
  const std::string path = CmuWalk();
  if (!fs::exists(path)) GTEST_SKIP() << path << " not present";
  const Scenario scenario = MakeScenario("bvh:" + path).value();
  const BodyPoseLimits lim;
  using J = Joint;
  double mean_rms = 0;
  for (size_t f = 0; f < scenario.target_skeletons.size(); ++f) {
    const Skeleton& target = scenario.target_skeletons[f];
    const BodyPoseFit fit = BodyPoseFromSkeleton(target);
    EXPECT_EQ(fit.bones_used, 13);
    EXPECT_EQ(fit.yaw_from, "hips");
    mean_rms += fit.rms_direction_error / scenario.target_skeletons.size();
    if (f % 5 != 0) continue;
    struct Dof {
      double* angle;
      double lo, hi;
      std::initializer_list<std::pair<Joint, Joint>> bones;
    };
    BodyPose p = fit.pose;
    const std::initializer_list<std::pair<Joint, Joint>> spine = {
        {J::kWaist, J::kTorso}, {J::kTorso, J::kNeck}, {J::kRightShoulder, J::kLeftShoulder}};
    const std::initializer_list<std::pair<Joint, Joint>> l_arm = {{J::kLeftShoulder, J::kLeftElbow},
                                                                  {J::kLeftElbow, J::kLeftHand}};
    const std::initializer_list<std::pair<Joint, Joint>> r_leg = {{J::kRightHip, J::kRightKnee},
                                                                  {J::kRightKnee, J::kRightFoot}};
    const std::initializer_list<std::pair<Joint, Joint>> head = {{J::kNeck, J::kHead}};
    const Dof dofs[] = {
        {&p.spine_bend, lim.spine_bend_min, lim.spine_bend_max, spine},
        {&p.spine_twist, -lim.spine_twist_max, lim.spine_twist_max, spine},
        {&p.head_pitch, -lim.head_pitch_max, lim.head_pitch_max, head},
        {&p.left_arm.abduction, lim.arm_abduction_min, lim.arm_abduction_max, l_arm},
        {&p.left_arm.flexion, lim.arm_flexion_min, lim.arm_flexion_max, l_arm},
        {&p.left_arm.elbow, 0, lim.elbow_max, l_arm},
        {&p.right_leg.abduction, lim.leg_abduction_min, lim.leg_abduction_max, r_leg},
        {&p.right_leg.flexion, lim.leg_flexion_min, lim.leg_flexion_max, r_leg},
        {&p.right_leg.knee, 0, lim.knee_max, r_leg},
    };
    for (const Dof& d : dofs) {
      const double at = *d.angle;
      const double cost = DirectionCost(PoseBody(p).skeleton, target, d.bones);
      for (double step : {-1e-3, 1e-3}) {
        if (at + step < d.lo || at + step > d.hi) continue;
        *d.angle = at + step;
        EXPECT_GE(DirectionCost(PoseBody(p).skeleton, target, d.bones), cost - 1e-9)
            << "frame " << f << " angle " << (d.angle - &p.spine_bend) << " step " << step;
        *d.angle = at;
      }
    }
    if (HasFailure()) break;
  }
  // A plausibility bound: the walk's unrepresentable turns are some degrees (the hip line
  // rolls up to 17 degrees in this clip), so the mean bone is within 0.2 (11.5 degrees).
  EXPECT_LT(mean_rms, 0.2);
}

}  // namespace
}  // namespace reenact::capture
