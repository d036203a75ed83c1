#include "synthetic/skinned_body.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <numbers>
#include <set>

#include "common/error/check.h"
#include "synthetic/body_model.h"
#include "synthetic/room.h"
#include "synthetic/scenario.h"
#include "tests/support/temp_dir.h"
#include "tests/unit/synthetic/gltf_test_rig.h"

namespace reenact::capture {
namespace {

using reenact::test_support::TempDir;

using Eigen::Matrix3d;
using Eigen::Vector3d;
using test::TestRig;
using test::TestRigOptions;

const std::string kCesiumMan = std::string(REENACT_SHARED_DATA_DIR) + "/models/CesiumMan.glb";

GltfSkinModel LoadRig(const TestRig& rig) {
  TempDir dir;
  rig.WriteGlb(dir.path() / "rig.glb");
  return LoadGltfSkin((dir.path() / "rig.glb").string()).value();
}

SkinnedBody RigBody(const TestRig& rig, const SkinnedBodyOptions& o = {}) {
  Expected<SkinnedBody> b = SkinnedBody::Create(LoadRig(rig), o);
  REENACT_CHECK(b.ok(), b.ok() ? "" : b.error().message);
  return std::move(b).value();
}

// The rig's world frame at the bind pose, by construction: the armature frame (z up, the
// model facing -y, its left +x) is the world frame at yaw 0 (world_from_body = WorldFromBody()),
// shifted so that the hips are above the origin and the lowest vertex (the soles, scene
// y = 0) is on the floor.
Vector3d RigWorld(const TestRig& rig, const Vector3d& scene) {
  const Vector3d a = test::ArmatureFromScene(scene);
  const Vector3d hips = test::ArmatureFromScene(rig.joints[0].scene);
  return Vector3d(a.x() - hips.x(), a.y() - hips.y(), a.z());
}

Vector3d Centroid(const TestRig& rig, const std::string& joint) {
  const int j = rig.JointIndex(joint);
  Vector3d sum = Vector3d::Zero();
  int n = 0;
  for (size_t i = 0; i < rig.positions.size(); ++i)
    if (rig.vertex_joints[i][0] == j && rig.vertex_weights[i][0] == 1.0) {
      sum += test::SceneFromArmature(rig.positions[i]);
      ++n;
    }
  return sum / n;
}

TEST(SkinnedBody, BindPoseReproducesTheMeshInTheWorldFrame) {
  const TestRig rig;
  const SkinnedBody body = RigBody(rig);
  EXPECT_NEAR(body.height_m(), 1.6 + 0.22, 1e-6);  // head box top minus the soles
  EXPECT_DOUBLE_EQ(body.metres_per_unit(), 1.0);
  const PosedSkin p = body.Skin(body.BindPose());
  ASSERT_EQ(p.positions.size(), rig.positions.size());
  for (size_t i = 0; i < rig.positions.size(); ++i) {
    EXPECT_LT((p.positions[i] - RigWorld(rig, test::SceneFromArmature(rig.positions[i]))).norm(),
              1e-6)
        << i;
    EXPECT_LT((p.normals[i] - rig.normals[i]).norm(), 1e-6) << i;  // world = armature axes
  }
}

TEST(SkinnedBody, HeightOptionScalesAboutTheFloorBelowTheWaist) {
  const TestRig rig;
  SkinnedBodyOptions o;
  o.height_m = 0.91;
  const SkinnedBody body = RigBody(rig, o);
  EXPECT_NEAR(body.height_m(), 0.91, 1e-9);
  EXPECT_NEAR(body.metres_per_unit(), 0.5, 1e-7);  // the file stores float32 positions
  const PosedSkin p = body.Skin(body.BindPose());
  for (size_t i = 0; i < rig.positions.size(); ++i)
    EXPECT_LT(
        (p.positions[i] - 0.5 * RigWorld(rig, test::SceneFromArmature(rig.positions[i]))).norm(),
        1e-6);
  o.height_m = -1;
  EXPECT_THROW(o.Check(), CheckError);
}

TEST(SkinnedBody, JointsOfTheBindPoseAreTheRigsJointsAndCentroids) {
  for (const std::string spine : {"Spine", "SpineLower"}) {
    TestRigOptions ro;
    ro.spine_name = spine;
    const TestRig rig(ro);
    const SkinnedBody body = RigBody(rig);
    const Skeleton s = body.Skin(body.BindPose()).skeleton;
    ASSERT_TRUE(s.Complete());
    const auto at = [&](const std::string& name) {
      return RigWorld(rig, rig.joints[rig.JointIndex(name)].scene);
    };
    const std::map<Joint, std::string> direct = {{Joint::kWaist, "Hips"},
                                                 {Joint::kNeck, "Neck"},
                                                 {Joint::kLeftShoulder, "LeftArm"},
                                                 {Joint::kLeftElbow, "LeftForeArm"},
                                                 {Joint::kRightShoulder, "RightArm"},
                                                 {Joint::kRightElbow, "RightForeArm"},
                                                 {Joint::kLeftHip, "LeftUpLeg"},
                                                 {Joint::kLeftKnee, "LeftLeg"},
                                                 {Joint::kLeftFoot, "LeftFoot"},
                                                 {Joint::kRightHip, "RightUpLeg"},
                                                 {Joint::kRightKnee, "RightLeg"},
                                                 {Joint::kRightFoot, "RightFoot"}};
    for (const auto& [j, name] : direct)
      EXPECT_LT((s[j] - at(name)).norm(), 1e-6) << spine << " " << JointName(j);
    EXPECT_LT((s[Joint::kHead] - RigWorld(rig, Centroid(rig, "Head"))).norm(), 1e-6);
    EXPECT_LT((s[Joint::kLeftHand] - RigWorld(rig, Centroid(rig, "LeftHand"))).norm(), 1e-6);
    EXPECT_LT((s[Joint::kRightHand] - RigWorld(rig, Centroid(rig, "RightHand"))).norm(), 1e-6);
    const Vector3d torso = spine == "Spine" ? at("Spine") : 0.5 * (at("Neck") + at("Hips"));
    EXPECT_LT((s[Joint::kTorso] - torso).norm(), 1e-6) << spine;
  }
}

TEST(SkinnedBody, OneRotatedJointMovesExactlyItsWeightedVerticesByThatRotation) {
  const TestRig rig;
  const SkinnedBody body = RigBody(rig);
  const int forearm = rig.JointIndex("LeftForeArm");
  const int hand = rig.JointIndex("LeftHand");
  const int upper = rig.JointIndex("LeftArm");
  // A rotation r in the forearm's own frame turns the forearm and what hangs on it about the
  // elbow by R = B r B^T in the world, B the forearm's bind rotation (world = armature axes).
  const Eigen::Quaterniond r(Eigen::AngleAxisd(0.7, Vector3d(0.3, -0.5, 0.8).normalized()));
  const Matrix3d big_r = rig.joints[forearm].rotation.toRotationMatrix() * r.toRotationMatrix() *
                         rig.joints[forearm].rotation.toRotationMatrix().transpose();
  SkinPose pose = body.BindPose();
  NodeTransform& t = pose.local[TestRig::Node(forearm)];
  t.rotation = t.rotation * r;
  const PosedSkin bind = body.Skin(body.BindPose());
  const PosedSkin posed = body.Skin(pose);
  const Vector3d elbow = RigWorld(rig, rig.joints[forearm].scene);
  int moved = 0, still = 0, blended = 0;
  for (size_t i = 0; i < rig.positions.size(); ++i) {
    const Vector3d p = bind.positions[i];
    const Vector3d turned = elbow + big_r * (p - elbow);
    const int j = rig.vertex_joints[i][0];
    const double w = rig.vertex_weights[i][0];
    if (w == 1.0 && (j == forearm || j == hand)) {
      EXPECT_LT((posed.positions[i] - turned).norm(), 1e-6) << i;
      EXPECT_LT((posed.normals[i] - big_r * bind.normals[i]).norm(), 1e-6) << i;
      ++moved;
    } else if (j == forearm && rig.vertex_joints[i][1] == upper) {
      EXPECT_LT((posed.positions[i] - (w * turned + (1 - w) * p)).norm(), 1e-6) << i;
      ++blended;
    } else {
      EXPECT_LT((posed.positions[i] - p).norm(), 1e-9) << i;
      EXPECT_LT((posed.normals[i] - bind.normals[i]).norm(), 1e-9) << i;
      ++still;
    }
  }
  EXPECT_EQ(moved, 16);
  EXPECT_EQ(blended, 8);
  EXPECT_GT(still, 100);
}

// A pose of the rig: the given local rotations (node -> rotation applied in the node's
// frame) and placement; then its skeleton with the lowest vertex on the floor.
Skeleton PosedTarget(const SkinnedBody& body, const std::map<int, Eigen::Quaterniond>& turns,
                     const Eigen::Isometry3d& world_from_body) {
  SkinPose pose = body.BindPose(world_from_body);
  for (const auto& [node, q] : turns) pose.local[node].rotation = pose.local[node].rotation * q;
  const PosedSkin p = body.Skin(pose);
  double lowest = 1e9;
  for (const Vector3d& v : p.positions) lowest = std::min(lowest, v.z());
  Skeleton s = p.skeleton;
  for (Vector3d& v : s.position) v.z() -= lowest;
  return s;
}

Eigen::Quaterniond Turn(double rad, const Vector3d& axis) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(rad, axis.normalized()));
}

TEST(SkinnedBody, RetargetingOntoItsOwnPoseReproducesIt) {
  for (const std::string spine : {"Spine", "SpineLower"}) {
    TestRigOptions ro;
    ro.spine_name = spine;
    const TestRig rig(ro);
    const SkinnedBody body = RigBody(rig);
    const auto node = [&](const std::string& n) { return TestRig::Node(rig.JointIndex(n)); };
    std::map<int, Eigen::Quaterniond> turns = {
        {node("Hips"), Turn(0.3, {0.2, 1, 0.4})},      {node("Neck"), Turn(0.4, {1, 0.3, 0})},
        {node("LeftArm"), Turn(1.1, {0, 1, 0.5})},     {node("LeftForeArm"), Turn(0.9, {1, 0, 0})},
        {node("RightArm"), Turn(-0.8, {1, 0.2, 0.1})}, {node("RightForeArm"), Turn(0.5, {0, 0, 1})},
        {node("LeftUpLeg"), Turn(0.7, {1, 0, 0.2})},   {node("LeftLeg"), Turn(-0.9, {1, 0, 0})},
        {node("RightUpLeg"), Turn(-0.3, {1, 0.4, 0})}, {node("RightLeg"), Turn(0.2, {1, 0, 0})}};
    // With a torso joint the chest may turn too; without one (the torso is derived from the
    // neck and waist) the pelvis takes its tilt from the whole spine, so only rotations that
    // keep the spine rigid on the pelvis can be reproduced.
    if (spine == "Spine") turns[node("Spine")] = Turn(0.35, {0.5, 0.2, 1});
    const Skeleton target = PosedTarget(body, turns, WorldFromBody({0.4, -0.7}, 2.0));
    const Expected<SkinPose> pose = body.RetargetPose(target);
    ASSERT_TRUE(pose.ok()) << pose.error().message;
    const PosedSkin got = body.Skin(*pose);
    // Joint positions fix each limb's direction but not its twist about it, so the feet may
    // turn a little about the shins and touch the floor with another vertex: the whole
    // skeleton may sit higher or lower by that, and only by that.
    const double dz = got.skeleton[Joint::kWaist].z() - target[Joint::kWaist].z();
    EXPECT_LT(std::abs(dz), 1e-3);
    for (int j = 0; j < kJointCount; ++j)
      EXPECT_LT((got.skeleton.position[j] - Vector3d(0, 0, dz) - target.position[j]).norm(), 1e-6)
          << spine << " " << JointName(static_cast<Joint>(j));
  }
}

// The unit direction from a to b.
Vector3d Dir(const Skeleton& s, Joint a, Joint b) { return (s[b] - s[a]).normalized(); }
// v with its component along the unit axis removed, normalised.
Vector3d Across(const Vector3d& v, const Vector3d& axis) {
  return (v - v.dot(axis) * axis).normalized();
}

TEST(SkinnedBody, RetargetingOntoTheProceduralBodyMatchesItsBoneDirections) {
  BodyPose kick;
  kick.right_leg.flexion = 1.3;
  kick.right_leg.knee = 0.4;
  kick.left_arm.flexion = 1.2;
  kick.left_arm.elbow = 1.4;
  kick.right_arm.abduction = 0.5;
  kick.root_yaw = 0.7;
  kick.root_xy = {0.3, -0.2};
  BodyPose bend;
  bend.spine_bend = 0.6;
  bend.spine_twist = 0.4;
  bend.head_pitch = 0.3;
  bend.left_leg.flexion = 0.8;
  bend.left_leg.knee = 1.5;
  bend.right_leg.flexion = 0.8;
  bend.right_leg.knee = 1.5;
  bend.left_arm.abduction = 1.5;
  bend.right_arm.abduction = 2.8;
  bend.root_yaw = -2.0;
  for (const std::string spine : {"Spine", "SpineLower"}) {
    TestRigOptions ro;
    ro.spine_name = spine;
    const SkinnedBody body = RigBody(TestRig(ro));
    for (const BodyPose& bp : {BodyPose{}, kick, bend}) {
      const Skeleton target = PoseBody(bp).skeleton;
      const Expected<SkinPose> pose = body.RetargetPose(target);
      ASSERT_TRUE(pose.ok()) << pose.error().message;
      const PosedSkin got = body.Skin(*pose);
      const Skeleton& s = got.skeleton;
      const std::vector<std::pair<Joint, Joint>> bones = {
          {Joint::kNeck, Joint::kHead},
          {Joint::kLeftShoulder, Joint::kLeftElbow},
          {Joint::kLeftElbow, Joint::kLeftHand},
          {Joint::kRightShoulder, Joint::kRightElbow},
          {Joint::kRightElbow, Joint::kRightHand},
          {Joint::kLeftHip, Joint::kLeftKnee},
          {Joint::kLeftKnee, Joint::kLeftFoot},
          {Joint::kRightHip, Joint::kRightKnee},
          {Joint::kRightKnee, Joint::kRightFoot}};
      for (const auto& [a, b] : bones)
        EXPECT_LT((Dir(s, a, b) - Dir(target, a, b)).norm(), 1e-6)
            << spine << " " << JointName(a) << "-" << JointName(b);
      const Vector3d hips_t = target[Joint::kLeftHip] - target[Joint::kRightHip];
      const Vector3d hips_s = s[Joint::kLeftHip] - s[Joint::kRightHip];
      const Vector3d sh_t = target[Joint::kLeftShoulder] - target[Joint::kRightShoulder];
      const Vector3d sh_s = s[Joint::kLeftShoulder] - s[Joint::kRightShoulder];
      if (spine == "Spine") {  // both spine bones, each with its line's twist
        const Vector3d lower = Dir(target, Joint::kWaist, Joint::kTorso);
        const Vector3d upper = Dir(target, Joint::kTorso, Joint::kNeck);
        EXPECT_LT((Dir(s, Joint::kWaist, Joint::kTorso) - lower).norm(), 1e-6);
        EXPECT_LT((Dir(s, Joint::kTorso, Joint::kNeck) - upper).norm(), 1e-6);
        EXPECT_LT((Across(hips_s, lower) - Across(hips_t, lower)).norm(), 1e-6);
        EXPECT_LT((Across(sh_s, upper) - Across(sh_t, upper)).norm(), 1e-6);
      } else {  // derived torso: the spine as one bone
        EXPECT_LT(
            (Dir(s, Joint::kWaist, Joint::kNeck) - Dir(target, Joint::kWaist, Joint::kNeck)).norm(),
            1e-6);
      }
      // Placement: waist above the target's, lowest vertex on the floor.
      EXPECT_LT((s[Joint::kWaist].head<2>() - target[Joint::kWaist].head<2>()).norm(), 1e-9);
      double lowest = 1e9;
      for (const Vector3d& v : got.positions) lowest = std::min(lowest, v.z());
      EXPECT_NEAR(lowest, 0.0, 1e-12);
    }
  }
}

TEST(SkinnedBody, RetargetingNeedsTheWaistAndHipsAndSkipsDegenerateBones) {
  const SkinnedBody body = RigBody(TestRig());
  Skeleton t = PoseBody(BodyPose{}).skeleton;
  t.confidence[Index(Joint::kLeftHip)] = 0;
  const Expected<SkinPose> none = body.RetargetPose(t);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().code, "invalid_argument");
  EXPECT_NE(none.error().message.find("l_hip"), std::string::npos);
  // A forearm of zero length and a missing knee: those bones keep their bind rotation.
  Skeleton d = PoseBody(BodyPose{}).skeleton;
  d[Joint::kLeftHand] = d[Joint::kLeftElbow];
  d.confidence[Index(Joint::kRightKnee)] = 0;
  const Expected<SkinPose> pose = body.RetargetPose(d);
  ASSERT_TRUE(pose.ok());
  const PosedSkin p = body.Skin(*pose);
  for (const Vector3d& v : p.positions) ASSERT_TRUE(v.allFinite());
  const SkinPose bind = body.BindPose();
  const int forearm = TestRig::Node(TestRig().JointIndex("LeftForeArm"));
  EXPECT_LT(pose->local[forearm].rotation.angularDistance(bind.local[forearm].rotation), 1e-12);
}

TEST(SkinnedBody, AnimationPoseTurnsTheAnimatedJointAndStandsOnTheFloor) {
  const TestRig rig;
  const SkinnedBody body = RigBody(rig);
  const PosedSkin bind = body.Skin(body.BindPose());
  const PosedSkin anim = body.Skin(body.AnimationPose(0, 1.0));
  // At t = 1 the forearm's local rotation is its rest rotation then 0.6 rad about its own z.
  const int forearm = rig.JointIndex("LeftForeArm");
  const Matrix3d b = rig.joints[forearm].rotation.toRotationMatrix();
  const Matrix3d r =
      b * Eigen::AngleAxisd(0.6, Vector3d::UnitZ()).toRotationMatrix() * b.transpose();
  const auto rel = [](const Skeleton& s, Joint a, Joint c) { return Vector3d(s[c] - s[a]); };
  EXPECT_LT((rel(anim.skeleton, Joint::kLeftElbow, Joint::kLeftHand) -
             r * rel(bind.skeleton, Joint::kLeftElbow, Joint::kLeftHand))
                .norm(),
            1e-6);
  EXPECT_LT((rel(anim.skeleton, Joint::kWaist, Joint::kLeftElbow) -
             rel(bind.skeleton, Joint::kWaist, Joint::kLeftElbow))
                .norm(),
            1e-6);
  double lowest = 1e9;
  for (const Vector3d& v : anim.positions) lowest = std::min(lowest, v.z());
  EXPECT_NEAR(lowest, 0.0, 1e-12);
}

TEST(SkinnedBody, VertexLabelsFollowTheDominantJoint) {
  const TestRig rig;
  const SkinnedBody body = RigBody(rig);
  const std::map<std::string, BodyPart> part = {{"Hips", BodyPart::kLowerTorso},
                                                {"Spine", BodyPart::kUpperTorso},
                                                {"Neck", BodyPart::kHead},
                                                {"Head", BodyPart::kHead},
                                                {"LeftArm", BodyPart::kLeftUpperArm},
                                                {"LeftForeArm", BodyPart::kLeftForearm},
                                                {"LeftHand", BodyPart::kLeftForearm},
                                                {"RightArm", BodyPart::kRightUpperArm},
                                                {"RightForeArm", BodyPart::kRightForearm},
                                                {"RightHand", BodyPart::kRightForearm},
                                                {"LeftUpLeg", BodyPart::kLeftThigh},
                                                {"LeftLeg", BodyPart::kLeftShin},
                                                {"LeftFoot", BodyPart::kLeftShin},
                                                {"RightUpLeg", BodyPart::kRightThigh},
                                                {"RightLeg", BodyPart::kRightShin},
                                                {"RightFoot", BodyPart::kRightShin}};
  ASSERT_EQ(body.vertex_parts().size(), rig.positions.size());
  for (size_t i = 0; i < rig.positions.size(); ++i) {
    const std::string& name = rig.joints[rig.vertex_joints[i][0]].name;  // dominant by build
    EXPECT_EQ(body.vertex_parts()[i], part.at(name)) << i << " " << name;
  }
  for (size_t j = 0; j < rig.joints.size(); ++j)
    EXPECT_EQ(body.JointPart(static_cast<int>(j)), part.at(rig.joints[j].name)) << j;
}

TEST(SkinnedBody, UnmappableOrUnchainedRigsAreUnsupported) {
  TestRig renamed;
  renamed.json["nodes"][TestRig::Node(renamed.JointIndex("LeftArm"))]["name"] = "Bob";
  Expected<SkinnedBody> b = SkinnedBody::Create(LoadRig(renamed));
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.error().code, "unsupported");
  EXPECT_NE(b.error().message.find("l_shoulder"), std::string::npos) << b.error().message;

  // The left forearm hung on the spine instead of the upper arm.
  TestRig moved;
  const int arm = TestRig::Node(moved.JointIndex("LeftArm"));
  const int fore = TestRig::Node(moved.JointIndex("LeftForeArm"));
  const int spine = TestRig::Node(moved.JointIndex("Spine"));
  moved.json["nodes"][arm].erase("children");
  moved.json["nodes"][spine]["children"].push_back(fore);
  b = SkinnedBody::Create(LoadRig(moved));
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.error().code, "unsupported");
  EXPECT_NE(b.error().message.find("is not below"), std::string::npos) << b.error().message;
}

SyntheticView Render(const SkinnedBody& body, const PosedSkin& posed, const PinholeCamera& camera,
                     const Eigen::Isometry3d& world_from_camera,
                     Image<double>* z_buffer = nullptr) {
  RasterOptions o;
  o.near_z = 0.05;
  o.attribute_count = 8;
  o.cull = CullMode::kBack;
  Rasterizer r(camera, o);
  SyntheticView v;
  v.color = ImageRgb8(camera.width, camera.height, 3, 0);
  v.depth = ImageDepthMm(camera.width, camera.height, 1, 0);
  v.mask = ImageGray8(camera.width, camera.height, 1, 0);
  v.part_labels = ImageLabel8(camera.width, camera.height, 1, 0);
  body.Draw(posed, world_from_camera.inverse(), &r, &v);
  if (z_buffer) *z_buffer = r.depth();
  return v;
}

TEST(SkinnedBody, DrawsTheBaseColourTimesTheShading) {
  TestRigOptions ro;
  ro.texture = false;  // colour factor (0.8, 0.4, 0.2)
  const SkinnedBody body = RigBody(TestRig(ro));
  const PinholeCamera camera = PinholeCamera::KinectLike();
  const SyntheticView v =
      Render(body, body.Skin(body.BindPose()), camera, LookAt({0.5, -3, 1.2}, {0, 0, 0.9}));
  int subject = 0;
  for (int y = 0; y < v.mask.height; ++y)
    for (int x = 0; x < v.mask.width; ++x) {
      EXPECT_EQ(v.mask.at(x, y) == 255, v.part_labels.at(x, y) != kBackgroundLabel);
      if (v.mask.at(x, y) != 255) continue;
      ++subject;
      // c = factor * shade * 255 rounded: r = 2 g = 4 b up to rounding.
      const double r = v.color.at(x, y, 0), g = v.color.at(x, y, 1), b = v.color.at(x, y, 2);
      EXPECT_NEAR(r, 2 * g, 1.5);
      EXPECT_NEAR(r, 4 * b, 2.5);
      EXPECT_LE(r, 0.8 * 255 + 0.5);
    }
  EXPECT_GT(subject, 2000);
  RasterOptions few;
  few.attribute_count = 7;
  Rasterizer r(camera, few);
  SyntheticView v2 = v;
  EXPECT_THROW(body.Draw(body.Skin(body.BindPose()), Eigen::Isometry3d::Identity(), &r, &v2),
               CheckError);
}

TEST(SkinnedBody, FrontalRenderOfCesiumManShowsEveryPartWhereItBelongs) {
  if (!std::filesystem::exists(kCesiumMan)) GTEST_SKIP() << kCesiumMan << " is absent";
  const Expected<SkinnedBody> body = SkinnedBody::Load(kCesiumMan);
  ASSERT_TRUE(body.ok()) << body.error().message;
  EXPECT_NEAR(body->height_m(), 1.5, 0.05);  // ../shared/data/README.md: about 1.5 m
  const PinholeCamera camera = PinholeCamera::KinectLike();
  const Eigen::Isometry3d world_from_camera = LookAt({0, -2.6, 0.9}, {0, 0, 0.8});
  const PosedSkin posed = body->Skin(body->BindPose());
  const SyntheticView v = Render(*body, posed, camera, world_from_camera);
  std::map<int, std::pair<Eigen::Vector2d, int>> stats;  // label -> (sum of pixels, count)
  std::set<int> colours;
  int top_row = v.mask.height, top_label = -1, bottom_row = -1, bottom_label = -1;
  for (int y = 0; y < v.mask.height; ++y)
    for (int x = 0; x < v.mask.width; ++x) {
      const int l = v.part_labels.at(x, y);
      if (l == kBackgroundLabel) continue;
      auto [it, fresh] = stats.try_emplace(l, Eigen::Vector2d::Zero(), 0);
      auto& [sum, n] = it->second;
      sum += Eigen::Vector2d(x, y);
      ++n;
      colours.insert(v.color.at(x, y, 0) << 16 | v.color.at(x, y, 1) << 8 | v.color.at(x, y, 2));
      if (y < top_row) top_row = y, top_label = l;
      if (y > bottom_row) bottom_row = y, bottom_label = l;
    }
  for (int p = 0; p < kBodyPartCount; ++p)
    EXPECT_GT(stats[PartLabel(static_cast<BodyPart>(p))].second, 50)
        << PartName(static_cast<BodyPart>(p));
  const auto mean = [&](BodyPart p) {
    const auto& [sum, n] = stats[PartLabel(p)];
    return Eigen::Vector2d(sum / std::max(n, 1));
  };
  // Up is up: head above the torso above the thighs above the shins (image y grows down);
  // the feet (labelled shin) are the lowest pixels, the head the highest.
  EXPECT_LT(mean(BodyPart::kHead).y(), mean(BodyPart::kUpperTorso).y());
  EXPECT_LT(mean(BodyPart::kUpperTorso).y(), mean(BodyPart::kLowerTorso).y());
  EXPECT_LT(mean(BodyPart::kLeftThigh).y(), mean(BodyPart::kLeftShin).y());
  EXPECT_LT(mean(BodyPart::kRightThigh).y(), mean(BodyPart::kRightShin).y());
  EXPECT_EQ(top_label, PartLabel(BodyPart::kHead));
  EXPECT_TRUE(bottom_label == PartLabel(BodyPart::kLeftShin) ||
              bottom_label == PartLabel(BodyPart::kRightShin));
  // Facing the camera: the subject's left is on the image's right.
  EXPECT_GT(mean(BodyPart::kLeftForearm).x(), mean(BodyPart::kRightForearm).x());
  EXPECT_GT(mean(BodyPart::kLeftThigh).x(), mean(BodyPart::kRightThigh).x());
  // Textured, not flat: many distinct colours.
  EXPECT_GT(colours.size(), 200u);
  // Every joint of the ground-truth skeleton projects onto the subject or within a few
  // pixels of it (joints lie inside the body).
  for (int j = 0; j < kJointCount; ++j) {
    const std::optional<Eigen::Vector2d> px =
        camera.Project(world_from_camera.inverse() * posed.skeleton.position[j]);
    ASSERT_TRUE(px.has_value());
    int nearest = 1 << 30;
    for (int y = 0; y < v.mask.height; ++y)
      for (int x = 0; x < v.mask.width; ++x)
        if (v.mask.at(x, y) == 255)
          nearest =
              std::min<int>(nearest, static_cast<int>((Eigen::Vector2d(x, y) - *px).squaredNorm()));
    EXPECT_LE(nearest, 9) << JointName(static_cast<Joint>(j));
  }
}

// Renders the posed body from each eye (looking at target, KinectLike camera) and calls
// visit(x, y, label, p) for every subject pixel, p its surface point in the world frame.
template <typename Visit>
void ForEachSurfacePixel(const SkinnedBody& body, const PosedSkin& posed,
                         std::initializer_list<Vector3d> eyes, const Vector3d& target,
                         Visit visit) {
  const PinholeCamera camera = PinholeCamera::KinectLike();
  for (const Vector3d& eye : eyes) {
    const Eigen::Isometry3d world_from_camera = LookAt(eye, target);
    Image<double> z_buffer;
    const SyntheticView v = Render(body, posed, camera, world_from_camera, &z_buffer);
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        const int l = v.part_labels.at(x, y);
        if (l == kBackgroundLabel) continue;
        const double z = z_buffer.at(x, y);
        visit(x, y, l,
              Vector3d(world_from_camera * Vector3d(z * (x - camera.cx) / camera.fx,
                                                    z * (y - camera.cy) / camera.fy, z)));
      }
  }
}

// The torso's two parts meet exactly at the torso joint's height on the surface (header:
// each pixel carries its surface point's part, not its triangle's). In the bind pose the
// split is the plane through the torso joint normal to waist -> neck (CesiumMan derives its
// torso joint as mean(neck, waist)), so every torso pixel lies on its label's side of it up
// to the depth buffer's precision; a label per triangle put lower-torso pixels up to about
// 6 cm above it on CesiumMan's low-polygon mesh.
TEST(SkinnedBody, TorsoPixelsSplitAtTheTorsoJoint) {
  if (!std::filesystem::exists(kCesiumMan)) GTEST_SKIP() << kCesiumMan << " is absent";
  const Expected<SkinnedBody> body = SkinnedBody::Load(kCesiumMan);
  ASSERT_TRUE(body.ok()) << body.error().message;
  const PosedSkin posed = body->Skin(body->BindPose());
  const Skeleton& k = posed.skeleton;
  const Vector3d up = (k[Joint::kNeck] - k[Joint::kWaist]).normalized();
  int near_upper = 0, near_lower = 0;
  ForEachSurfacePixel(*body, posed, {Vector3d(0, -2.6, 0.9), Vector3d(1.5, -2, 1.6)}, {0, 0, 0.8},
                      [&](int x, int y, int l, const Vector3d& p) {
                        const bool upper = l == PartLabel(BodyPart::kUpperTorso);
                        if (!upper && l != PartLabel(BodyPart::kLowerTorso)) return;
                        const double s = (p - k[Joint::kTorso]).dot(up);
                        EXPECT_TRUE(upper ? s > -0.002 : s < 0.002)
                            << x << " " << y << " " << l << " " << s;
                        if (std::abs(s) < 0.01) ++(upper ? near_upper : near_lower);
                      });
  EXPECT_GT(near_upper, 20);
  EXPECT_GT(near_lower, 20);
}

// A rig's neck joint moves the neck above it, which lies along the head's cylinder (neck ->
// head), so its skin is labelled head: no torso pixel lies more than 1 cm above the neck
// joint along waist -> neck, and the neck between the neck joint and the rig's head node,
// within 5 cm of the spine's line, is head.
TEST(SkinnedBody, NeckSkinAboveTheNeckJointIsHead) {
  if (!std::filesystem::exists(kCesiumMan)) GTEST_SKIP() << kCesiumMan << " is absent";
  const Expected<SkinnedBody> body = SkinnedBody::Load(kCesiumMan);
  ASSERT_TRUE(body.ok()) << body.error().message;
  const PosedSkin posed = body->Skin(body->BindPose());
  const Skeleton& k = posed.skeleton;
  const Vector3d up = (k[Joint::kNeck] - k[Joint::kWaist]).normalized();
  int neck_pixels = 0;
  ForEachSurfacePixel(
      *body, posed, {Vector3d(0, -2.6, 1.2), Vector3d(1.5, -2, 1.6)}, {0, 0, 1.0},
      [&](int x, int y, int l, const Vector3d& p) {
        const Vector3d from_neck = p - k[Joint::kNeck];
        const double s = from_neck.dot(up);
        if (l == PartLabel(BodyPart::kUpperTorso) || l == PartLabel(BodyPart::kLowerTorso)) {
          EXPECT_LT(s, 0.01) << x << " " << y << " " << l;
        }
        const double across = (from_neck - s * up).norm();
        if (s > 0.01 && s < 0.04 && across < 0.05) {
          EXPECT_EQ(l, PartLabel(BodyPart::kHead)) << x << " " << y << " " << s;
          ++neck_pixels;
        }
      });
  EXPECT_GT(neck_pixels, 50);
}

}  // namespace
}  // namespace reenact::capture
