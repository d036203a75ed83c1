#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "synthetic/body_mesh.h"
#include "synthetic/body_model.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture {
namespace {

const SyntheticScene& Scene() {
  static const SyntheticScene scene = SyntheticScene::Create("turn-and-kick").value();
  return scene;
}

// Facing direction on the floor from anatomy alone: shoulders left-minus-right, crossed
// with up, points forwards.
double FacingAngle(const Skeleton& sk) {
  const Eigen::Vector3d left = sk[Joint::kLeftShoulder] - sk[Joint::kRightShoulder];
  const Eigen::Vector3d forward = left.cross(Eigen::Vector3d::UnitZ());
  return std::atan2(forward.y(), forward.x());
}

TEST(SyntheticBody, BoneLengthsAreConstantOverTheClip) {
  const SyntheticScene& s = Scene();
  const Skeleton first = s.skeleton_in_world(0);
  for (int frame = 1; frame < s.frame_count(); ++frame) {
    const Skeleton sk = s.skeleton_in_world(frame);
    for (int p = 0; p < kBodyPartCount; ++p) {
      const auto [a, b] = PartJoints(static_cast<BodyPart>(p));
      EXPECT_NEAR((sk[a] - sk[b]).norm(), (first[a] - first[b]).norm(), 1e-9)
          << "frame " << frame << " " << PartName(static_cast<BodyPart>(p));
    }
  }
}

TEST(SyntheticBody, ProportionsOfAnAdult) {
  const Skeleton sk = Scene().skeleton_in_world(0);
  EXPECT_NEAR(sk[Joint::kLeftFoot].z(), 0.08, 0.01);  // ankles above the floor
  EXPECT_NEAR(sk[Joint::kRightFoot].z(), 0.08, 0.01);
  EXPECT_NEAR(sk[Joint::kHead].z(), 1.63, 0.04);  // centre of the head
  EXPECT_NEAR(sk[Joint::kWaist].z(), 1.0, 0.05);
  const double shoulders = (sk[Joint::kLeftShoulder] - sk[Joint::kRightShoulder]).norm();
  EXPECT_GT(shoulders, 0.32);
  EXPECT_LT(shoulders, 0.42);
  const double leg = (sk[Joint::kLeftHip] - sk[Joint::kLeftKnee]).norm() +
                     (sk[Joint::kLeftKnee] - sk[Joint::kLeftFoot]).norm();
  EXPECT_NEAR(leg, 0.84, 0.06);
  // Calibration pose: arms held out horizontally to the sides.
  const Eigen::Vector3d arm = sk[Joint::kLeftHand] - sk[Joint::kLeftShoulder];
  EXPECT_LT(std::abs(arm.normalized().z()), 0.1);
}

TEST(SyntheticBody, FacesTheSensorFirstThenTurnsAFullCircle) {
  const SyntheticScene& s = Scene();
  const Eigen::Vector3d sensor = s.world_from_sensor(0).translation();
  const Skeleton first = s.skeleton_in_world(0);
  const Eigen::Vector3d to_sensor = (sensor - first[Joint::kWaist]).normalized();
  const double a0 = FacingAngle(first);
  EXPECT_GT(std::cos(a0) * to_sensor.x() + std::sin(a0) * to_sensor.y(), 0.9);

  bool quadrant[4] = {false, false, false, false};
  double unwrapped = 0, previous = a0;
  for (int frame = 1; frame < s.frame_count(); ++frame) {
    const double a = FacingAngle(s.skeleton_in_world(frame));
    double step = a - previous;
    step = std::remainder(step, 2 * std::numbers::pi);
    unwrapped += step;
    previous = a;
    const double rel = std::remainder(a - a0, 2 * std::numbers::pi);
    quadrant[static_cast<int>(std::floor((rel + std::numbers::pi) / (std::numbers::pi / 2))) % 4] =
        true;
  }
  for (int q = 0; q < 4; ++q) EXPECT_TRUE(quadrant[q]) << q;
  EXPECT_NEAR(std::abs(unwrapped), 2 * std::numbers::pi, 0.35);
}

TEST(SyntheticBody, KickRaisesTheRightFootAndTheArmGoesOverhead) {
  const SyntheticScene& s = Scene();
  double max_foot = 0, max_hand = 0;
  for (int frame = 0; frame < s.frame_count(); ++frame) {
    const Skeleton sk = s.skeleton_in_world(frame);
    max_foot = std::max(max_foot, sk[Joint::kRightFoot].z());
    max_hand = std::max(max_hand, sk[Joint::kRightHand].z() - sk[Joint::kHead].z());
    // Standing on the floor throughout.
    EXPECT_NEAR(std::min(sk[Joint::kLeftFoot].z(), sk[Joint::kRightFoot].z()), 0.08, 1e-9);
  }
  EXPECT_GT(max_foot, 0.6);
  EXPECT_GT(max_hand, 0.3);
}

// Signed volume of a closed mesh (divergence theorem); positive when wound outwards.
double Volume(const SegmentMesh& m) {
  double v = 0;
  for (const Eigen::Vector3i& t : m.triangles)
    v += m.positions[t[0]].dot(m.positions[t[1]].cross(m.positions[t[2]])) / 6.0;
  return v;
}

TEST(SyntheticBody, MeshesAreClosedOutwardAndOfHumanVolume) {
  const auto meshes = BuildBodyMeshes();
  double total = 0;
  int triangles = 0;
  for (int s = 0; s < kSegmentCount; ++s) {
    const double v = Volume(meshes[s]);
    EXPECT_GT(v, 0) << s;
    total += v;
    triangles += static_cast<int>(meshes[s].triangles.size());
  }
  // A 70 kg adult at a density of about 1 kg/l is about 0.07 m^3; the capsules overlap at
  // the joints, so allow a wide band.
  EXPECT_GT(total, 0.05);
  EXPECT_LT(total, 0.10);
  EXPECT_LT(triangles, 20000);
}

TEST(SyntheticBody, TorsoIsWiderThanDeepAndHeadIsAnEllipsoid) {
  const auto meshes = BuildBodyMeshes();
  auto extent = [](const SegmentMesh& m) {
    Eigen::Vector3d lo = m.positions[0], hi = m.positions[0];
    for (const auto& p : m.positions) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    return Eigen::Vector3d(hi - lo);
  };
  const Eigen::Vector3d torso = extent(meshes[static_cast<int>(Segment::kUpperTorso)]);
  EXPECT_GT(torso.y(), 1.3 * torso.x());
  const Eigen::Vector3d head = extent(meshes[static_cast<int>(Segment::kHead)]);
  EXPECT_NEAR(head.z(), 0.24, 0.01);
  EXPECT_GT(head.x(), head.y());
}

TEST(SyntheticBody, StandingSubjectIsAbout175Tall) {
  const auto meshes = BuildBodyMeshes();
  const PosedBody body = PoseBody(BodyPose{});
  double top = -1, bottom = 10;
  for (int s = 0; s < kSegmentCount; ++s)
    for (const auto& p : meshes[s].positions) {
      const double z = (body.world_from_segment[s] * p).z();
      top = std::max(top, z);
      bottom = std::min(bottom, z);
    }
  EXPECT_NEAR(top, 1.75, 0.03);
  EXPECT_NEAR(bottom, 0.0, 0.01);
}

}  // namespace
}  // namespace reenact::capture
