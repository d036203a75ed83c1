#include "common/skeleton/joint_maps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "common/error/check.h"

namespace reenact {
namespace {

// Distinct, recognisable positions: source joint i sits at (i, 10 + i, 100 + i) / 100.
std::vector<Eigen::Vector3d> IndexedPositions(size_t n) {
  std::vector<Eigen::Vector3d> p;
  for (size_t i = 0; i < n; ++i) p.emplace_back(0.01 * i, 0.1 + 0.01 * i, 1.0 + 0.01 * i);
  return p;
}

void ExpectJointAt(const Skeleton& s, Joint j, const Eigen::Vector3d& expected, double conf = 1) {
  ASSERT_TRUE(s.Has(j)) << JointName(j);
  EXPECT_LT((s[j] - expected).norm(), 1e-12) << JointName(j);
  EXPECT_DOUBLE_EQ(s.confidence[Index(j)], conf) << JointName(j);
}

TEST(JointMaps, KinectV1MapsSdkIndices) {
  const JointSetDefinition& def = KinectV1Joints();
  ASSERT_EQ(def.source_names.size(), 20u);
  const auto p = IndexedPositions(20);
  // NUI_SKELETON_POSITION_INDEX: 0 HipCenter, 1 Spine, 2 ShoulderCenter, 3 Head,
  // 4-7 Shoulder/Elbow/Wrist/Hand Left, 8-11 Right, 12-15 Hip/Knee/Ankle/Foot Left, 16-19 Right.
  const Expected<Skeleton> s = MapSkeleton(def, p);
  ASSERT_TRUE(s.ok());
  EXPECT_TRUE(s->Complete());
  ExpectJointAt(*s, Joint::kWaist, p[0]);
  ExpectJointAt(*s, Joint::kTorso, p[1]);
  ExpectJointAt(*s, Joint::kNeck, p[2]);
  ExpectJointAt(*s, Joint::kHead, p[3]);
  ExpectJointAt(*s, Joint::kLeftShoulder, p[4]);
  ExpectJointAt(*s, Joint::kLeftElbow, p[5]);
  ExpectJointAt(*s, Joint::kLeftHand, p[7]);
  ExpectJointAt(*s, Joint::kRightShoulder, p[8]);
  ExpectJointAt(*s, Joint::kRightElbow, p[9]);
  ExpectJointAt(*s, Joint::kRightHand, p[11]);
  ExpectJointAt(*s, Joint::kLeftHip, p[12]);
  ExpectJointAt(*s, Joint::kLeftKnee, p[13]);
  ExpectJointAt(*s, Joint::kLeftFoot, p[14]);
  ExpectJointAt(*s, Joint::kRightHip, p[16]);
  ExpectJointAt(*s, Joint::kRightKnee, p[17]);
  ExpectJointAt(*s, Joint::kRightFoot, p[18]);
}

TEST(JointMaps, KinectV1FallsBackToWristAndFootAndKeepsInferredConfidence) {
  const auto p = IndexedPositions(20);
  std::vector<double> conf(20, 1.0);
  conf[7] = 0;     // HandLeft not tracked
  conf[6] = 0.5;   // WristLeft inferred
  conf[18] = 0;    // AnkleRight not tracked
  conf[3] = 0.25;  // Head inferred
  const Expected<Skeleton> s = MapSkeleton(KinectV1Joints(), p, conf);
  ASSERT_TRUE(s.ok());
  ExpectJointAt(*s, Joint::kLeftHand, p[6], 0.5);
  ExpectJointAt(*s, Joint::kRightFoot, p[19]);
  ExpectJointAt(*s, Joint::kHead, p[3], 0.25);
}

TEST(JointMaps, NiteWaistIsTheMidpointOfTheHips) {
  const auto p = IndexedPositions(15);
  const Expected<Skeleton> s = MapSkeleton(NiteJoints(), p);
  ASSERT_TRUE(s.ok());
  EXPECT_TRUE(s->Complete());
  // XnSkeletonJoint order without the untracked joints: our order with the waist left out.
  ExpectJointAt(*s, Joint::kHead, p[0]);
  ExpectJointAt(*s, Joint::kNeck, p[1]);
  ExpectJointAt(*s, Joint::kTorso, p[2]);
  ExpectJointAt(*s, Joint::kLeftHand, p[5]);
  ExpectJointAt(*s, Joint::kRightShoulder, p[6]);
  ExpectJointAt(*s, Joint::kLeftHip, p[9]);
  ExpectJointAt(*s, Joint::kRightFoot, p[14]);
  ExpectJointAt(*s, Joint::kWaist, 0.5 * (p[9] + p[12]));

  // NiTE 2's nite::JointType order.
  const Expected<Skeleton> s2 = MapSkeleton(Nite2Joints(), p);
  ASSERT_TRUE(s2.ok());
  ExpectJointAt(*s2, Joint::kLeftShoulder, p[2]);
  ExpectJointAt(*s2, Joint::kRightHand, p[7]);
  ExpectJointAt(*s2, Joint::kTorso, p[8]);
  ExpectJointAt(*s2, Joint::kWaist, 0.5 * (p[9] + p[10]));
  ExpectJointAt(*s2, Joint::kRightFoot, p[14]);
}

TEST(JointMaps, MissingSourceJointsGiveMissingJointsNeverNaN) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto p = IndexedPositions(15);
  std::vector<double> conf(15, 1.0);
  conf[12] = 0;                       // RIGHT_HIP lost: the hip and the waist (its mean) go
  p[4] = Eigen::Vector3d(nan, 0, 0);  // LEFT_ELBOW reported as NaN with confidence 1
  const Expected<Skeleton> s = MapSkeleton(NiteJoints(), p, conf);
  ASSERT_TRUE(s.ok());
  EXPECT_FALSE(s->Has(Joint::kRightHip));
  EXPECT_FALSE(s->Has(Joint::kWaist));
  EXPECT_FALSE(s->Has(Joint::kLeftElbow));
  EXPECT_TRUE(s->Has(Joint::kLeftHip));
  for (int j = 0; j < kJointCount; ++j) EXPECT_TRUE(s->position[j].allFinite()) << j;

  const Expected<Skeleton> none =
      MapSkeleton(KinectV1Joints(), IndexedPositions(20), std::vector<double>(20, 0.0));
  ASSERT_TRUE(none.ok());
  for (int j = 0; j < kJointCount; ++j) {
    EXPECT_EQ(none->confidence[j], 0.0);
    EXPECT_EQ(none->position[j], Eigen::Vector3d::Zero());
  }
}

TEST(JointMaps, BadInputIsAnError) {
  EXPECT_EQ(MapSkeleton(NiteJoints(), IndexedPositions(14)).error().code, "invalid_argument");
  EXPECT_EQ(
      MapSkeleton(NiteJoints(), IndexedPositions(15), std::vector<double>(3, 1.0)).error().code,
      "invalid_argument");
  std::vector<double> conf(15, 1.0);
  conf[3] = 1.5;
  EXPECT_FALSE(MapSkeleton(NiteJoints(), IndexedPositions(15), conf).ok());
  conf[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(MapSkeleton(NiteJoints(), IndexedPositions(15), conf).ok());

  EXPECT_EQ(JointsByName({}).error().code, "invalid_argument");
  EXPECT_EQ(JointsByName({"LeftArm", "left_arm"}).error().code, "invalid_argument");
  EXPECT_EQ(GltfJointsByName({"Armature", "Bone.001"}).error().code, "invalid_argument");
}

TEST(JointMaps, MalformedDefinitionIsABug) {
  JointSetDefinition def;
  def.source_names = {"a", "b"};
  def.recipes[0].push_back(JointRecipe{{0, 5}, {0.5, 0.5}});  // index 5 out of range
  EXPECT_THROW(def.Check(), CheckError);
  def.recipes[0] = {JointRecipe{{0, 1}, {0.5, 0.6}}};  // weights sum to 1.1
  EXPECT_THROW(def.Check(), CheckError);
}

// The joint names and rest-pose offsets of a BVH file's HIERARCHY section.
struct BvhRig {
  std::vector<std::string> names;
  std::vector<Eigen::Vector3d> rest_position;  // sum of offsets from the root, file units
};

BvhRig ReadBvhHierarchy(const std::string& path) {
  std::ifstream in(path);
  BvhRig rig;
  std::vector<int> stack;  // joint index per open brace, -1 for an End Site
  std::string token;
  int pending = -1;
  while (in >> token && token != "MOTION") {
    if (token == "ROOT" || token == "JOINT") {
      in >> token;
      rig.names.push_back(token);
      rig.rest_position.push_back(Eigen::Vector3d::Zero());
      pending = static_cast<int>(rig.names.size()) - 1;
    } else if (token == "End") {
      pending = -1;
    } else if (token == "{") {
      stack.push_back(pending);
    } else if (token == "}") {
      stack.pop_back();
    } else if (token == "OFFSET") {
      Eigen::Vector3d offset;
      in >> offset.x() >> offset.y() >> offset.z();
      const int self = stack.back();
      if (self < 0) continue;
      int parent = -1;
      for (size_t i = stack.size() - 1; i-- > 0;)
        if (stack[i] >= 0) {
          parent = stack[i];
          break;
        }
      rig.rest_position[self] =
          (parent >= 0 ? rig.rest_position[parent] : Eigen::Vector3d::Zero()) + offset;
    }
  }
  return rig;
}

TEST(JointMaps, CmuBvhFromTheRealFileResolvesEveryJoint) {
  const BvhRig rig =
      ReadBvhHierarchy(std::string(REENACT_SHARED_DATA_DIR) + "/mocap/cmu-131_01-walk.bvh");
  ASSERT_EQ(rig.names.size(), 31u);
  EXPECT_EQ(rig.names, CmuBvhJoints().source_names);

  const Expected<Skeleton> s = MapSkeleton(CmuBvhJoints(), rig.rest_position);
  ASSERT_TRUE(s.ok());
  ASSERT_TRUE(s->Complete());
  // Rest pose, Y up, metres: the chain from the head down to the waist runs downwards, the
  // hips sit about 0.95 m above the feet (README), legs and arms have human lengths.
  EXPECT_GT((*s)[Joint::kHead].y(), (*s)[Joint::kNeck].y());
  EXPECT_GT((*s)[Joint::kNeck].y(), (*s)[Joint::kTorso].y());
  EXPECT_GT((*s)[Joint::kTorso].y(), (*s)[Joint::kWaist].y());
  EXPECT_NEAR((*s)[Joint::kWaist].y() - (*s)[Joint::kLeftFoot].y(), 0.9, 0.1);
  for (auto [a, b] : {std::pair{Joint::kLeftHip, Joint::kLeftKnee},
                      std::pair{Joint::kRightKnee, Joint::kRightFoot},
                      std::pair{Joint::kLeftShoulder, Joint::kLeftElbow}}) {
    const double length = ((*s)[a] - (*s)[b]).norm();
    EXPECT_GT(length, 0.2) << JointName(a);
    EXPECT_LT(length, 0.55) << JointName(a);
  }
  // Left and right lie on opposite sides of the body's midline.
  EXPECT_LT(((*s)[Joint::kLeftHip].x() - (*s)[Joint::kWaist].x()) *
                ((*s)[Joint::kRightHip].x() - (*s)[Joint::kWaist].x()),
            0);

  // The same names through the by-name matcher give the same joints (in file units).
  const Expected<JointSetDefinition> by_name = JointsByName(rig.names, "bvh");
  ASSERT_TRUE(by_name.ok());
  const Expected<Skeleton> t = MapSkeleton(*by_name, rig.rest_position);
  ASSERT_TRUE(t.ok());
  ASSERT_TRUE(t->Complete());
  for (int j = 0; j < kJointCount; ++j)
    EXPECT_LT((t->position[j] * CmuBvhJoints().metres_per_unit - s->position[j]).norm(), 1e-12)
        << JointName(static_cast<Joint>(j));
}

TEST(JointMaps, CesiumManGltfSkinResolvesEveryJoint) {
  // skins[0].joints of CesiumMan.glb, in order.
  const std::vector<std::string> names = {"Skeleton_torso_joint_1",
                                          "Skeleton_torso_joint_2",
                                          "torso_joint_3",
                                          "Skeleton_neck_joint_1",
                                          "Skeleton_neck_joint_2",
                                          "Skeleton_arm_joint_L__4_",
                                          "Skeleton_arm_joint_R",
                                          "Skeleton_arm_joint_L__3_",
                                          "Skeleton_arm_joint_R__2_",
                                          "Skeleton_arm_joint_L__2_",
                                          "Skeleton_arm_joint_R__3_",
                                          "leg_joint_L_1",
                                          "leg_joint_R_1",
                                          "leg_joint_L_2",
                                          "leg_joint_R_2",
                                          "leg_joint_L_3",
                                          "leg_joint_R_3",
                                          "leg_joint_L_5",
                                          "leg_joint_R_5"};
  std::ifstream in(std::string(REENACT_SHARED_DATA_DIR) + "/models/CesiumMan.glb",
                   std::ios::binary);
  const std::string glb((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(glb.empty());
  for (const std::string& n : names) EXPECT_NE(glb.find("\"" + n + "\""), std::string::npos) << n;

  const Expected<JointSetDefinition> def = GltfJointsByName(names);
  ASSERT_TRUE(def.ok());
  const auto p = IndexedPositions(names.size());
  const Expected<Skeleton> s = MapSkeleton(*def, p);
  ASSERT_TRUE(s.ok());
  ASSERT_TRUE(s->Complete());
  ExpectJointAt(*s, Joint::kWaist, p[0]);
  ExpectJointAt(*s, Joint::kNeck, p[3]);
  ExpectJointAt(*s, Joint::kHead, p[4]);
  ExpectJointAt(*s, Joint::kTorso, 0.5 * (p[3] + p[0]));  // no torso name: mean(neck, waist)
  ExpectJointAt(*s, Joint::kLeftShoulder, p[5]);
  ExpectJointAt(*s, Joint::kLeftElbow, p[7]);
  ExpectJointAt(*s, Joint::kLeftHand, p[9]);
  ExpectJointAt(*s, Joint::kRightShoulder, p[6]);
  ExpectJointAt(*s, Joint::kRightElbow, p[8]);
  ExpectJointAt(*s, Joint::kRightHand, p[10]);
  ExpectJointAt(*s, Joint::kLeftHip, p[11]);
  ExpectJointAt(*s, Joint::kLeftKnee, p[13]);
  ExpectJointAt(*s, Joint::kLeftFoot, p[15]);
  ExpectJointAt(*s, Joint::kRightFoot, p[16]);
}

TEST(JointMaps, ByNamePrefersTheUpperArmOverTheClavicleAndIgnoresCaseAndPrefixes) {
  const std::vector<std::string> names = {
      "mixamorig:Hips",     "mixamorig:Spine",       "mixamorig:Spine1",
      "mixamorig:Neck",     "mixamorig:Head",        "mixamorig:LeftShoulder",
      "mixamorig:LeftArm",  "mixamorig:LeftForeArm", "mixamorig:LeftHand",
      "MIXAMORIG:RIGHTARM", "mixamorig:LeftUpLeg",   "mixamorig:LeftLeg",
      "mixamorig:LeftFoot"};
  const Expected<JointSetDefinition> def = JointsByName(names);
  ASSERT_TRUE(def.ok());
  const auto p = IndexedPositions(names.size());
  const Expected<Skeleton> s = MapSkeleton(*def, p);
  ASSERT_TRUE(s.ok());
  ExpectJointAt(*s, Joint::kTorso, p[2]);
  ExpectJointAt(*s, Joint::kLeftShoulder, p[6]);
  ExpectJointAt(*s, Joint::kLeftElbow, p[7]);
  ExpectJointAt(*s, Joint::kRightShoulder, p[9]);
  ExpectJointAt(*s, Joint::kLeftKnee, p[11]);
  ExpectJointAt(*s, Joint::kLeftFoot, p[12]);
  EXPECT_FALSE(s->Has(Joint::kRightHip));  // no name for it: missing, not an error
  EXPECT_EQ(NormalizeJointName("Armature|upper_arm.L"), "upperarml");
}

TEST(JointMaps, ByNameAgreesWithTheBuiltInTables) {
  for (const JointSetDefinition* table : {&KinectV1Joints(), &NiteJoints(), &Nite2Joints()}) {
    const Expected<JointSetDefinition> def = JointsByName(table->source_names);
    ASSERT_TRUE(def.ok()) << table->name;
    const auto p = IndexedPositions(table->source_names.size());
    std::vector<double> conf(p.size(), 1.0);
    conf[0] = 0;  // exercises the fallbacks as well
    const Skeleton a = MapSkeleton(*table, p, conf).value();
    const Skeleton b = MapSkeleton(*def, p, conf).value();
    for (int j = 0; j < kJointCount; ++j) {
      EXPECT_EQ(a.confidence[j], b.confidence[j]) << table->name << " " << j;
      EXPECT_LT((a.position[j] - b.position[j]).norm(), 1e-12) << table->name << " " << j;
    }
  }
}

TEST(NeckRelative, SubtractsTheNeckAndKeepsMissingJointsMissing) {
  Skeleton s;
  s.Set(Joint::kNeck, {1, 2, 3});
  s.Set(Joint::kHead, {1, 1.8, 3}, 0.5);
  s.Set(Joint::kLeftHand, {1.5, 2, 3});
  s.confidence[Index(Joint::kLeftHand)] = 0;
  const std::optional<Skeleton> r = NeckRelative(s);
  ASSERT_TRUE(r);
  EXPECT_EQ((*r)[Joint::kNeck], Eigen::Vector3d::Zero());
  EXPECT_LT(((*r)[Joint::kHead] - Eigen::Vector3d(0, -0.2, 0)).norm(), 1e-12);
  EXPECT_EQ(r->confidence[Index(Joint::kHead)], 0.5);
  EXPECT_FALSE(r->Has(Joint::kLeftHand));
  EXPECT_EQ((*r)[Joint::kLeftHand], Eigen::Vector3d::Zero());
  EXPECT_FALSE(NeckRelative(Skeleton{}));
}

}  // namespace
}  // namespace reenact
