#include "synthetic/gltf_skin.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "tests/unit/synthetic/gltf_test_rig.h"

namespace reenact::capture {
namespace {

using test::TestRig;
using test::TestRigOptions;

const std::string kCesiumMan = std::string(REENACT_SHARED_DATA_DIR) + "/models/CesiumMan.glb";

class GltfSkinTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string t = (std::filesystem::temp_directory_path() / "reenact-gltf-XXXXXX").string();
    ASSERT_NE(mkdtemp(t.data()), nullptr);
    dir_ = t;
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string Write(const TestRig& rig, const std::string& name) {
    const std::filesystem::path p = dir_ / name;
    if (p.extension() == ".glb")
      rig.WriteGlb(p);
    else
      rig.WriteGltf(p);
    return p.string();
  }
  // Writes the rig after `mutate` changed its JSON, loads it and expects an error.
  void ExpectError(const std::function<void(TestRig&)>& mutate, const std::string& code,
                   const std::string& says, const TestRigOptions& options = {}) {
    TestRig rig(options);
    mutate(rig);
    const std::string path = Write(rig, "broken.gltf");
    const Expected<GltfSkinModel> m = LoadGltfSkin(path);
    ASSERT_FALSE(m.ok()) << "expected an error saying '" << says << "'";
    EXPECT_EQ(m.error().code, code) << m.error().message;
    EXPECT_NE(m.error().message.find(says), std::string::npos) << m.error().message;
    EXPECT_NE(m.error().message.find(path), std::string::npos) << m.error().message;
  }

  std::filesystem::path dir_;
};

double QuaternionDistance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return std::min((a.coeffs() - b.coeffs()).norm(), (a.coeffs() + b.coeffs()).norm());
}

TEST_F(GltfSkinTest, ReadsTheRigFromGltfAndGlbAlike) {
  const TestRig rig;
  for (const std::string name : {"rig.gltf", "rig.glb"}) {
    const Expected<GltfSkinModel> m = LoadGltfSkin(Write(rig, name));
    ASSERT_TRUE(m.ok()) << m.error().message;
    EXPECT_TRUE(m->warnings.empty()) << m->warnings.front();
    ASSERT_EQ(m->vertices.size(), rig.positions.size());
    ASSERT_EQ(m->triangles.size(), rig.triangles.size());
    for (size_t i = 0; i < rig.positions.size(); ++i) {
      const SkinVertex& v = m->vertices[i];
      EXPECT_LT((v.position - rig.positions[i]).norm(), 1e-6) << i;
      EXPECT_LT((v.normal - rig.normals[i]).norm(), 1e-6) << i;
      EXPECT_LT((v.uv - rig.uvs[i]).norm(), 1e-6) << i;
      EXPECT_EQ(v.joints[0], rig.vertex_joints[i][0]) << i;
      EXPECT_NEAR(v.weights.sum(), 1.0, 1e-12) << i;
      EXPECT_NEAR(v.weights[0], rig.vertex_weights[i][0], 1e-6) << i;
    }
    for (size_t t = 0; t < rig.triangles.size(); ++t) EXPECT_EQ(m->triangles[t], rig.triangles[t]);
    ASSERT_EQ(m->joint_nodes.size(), rig.joints.size());
    for (size_t j = 0; j < rig.joints.size(); ++j) {
      EXPECT_EQ(m->joint_nodes[j], TestRig::Node(static_cast<int>(j)));
      EXPECT_EQ(m->JointNames()[j], rig.joints[j].name);
    }
    EXPECT_EQ(m->mesh_node, 1);
    EXPECT_EQ(m->nodes[TestRig::Node(0)].parent, 0);
    // Texture: RGB of the BGR test image; wrap modes REPEAT in u, CLAMP_TO_EDGE in v.
    ASSERT_EQ(m->base_color_texture.image.width, 4);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(m->base_color_texture.image.at(x, y, c),
                    rig.texture.at<cv::Vec3b>(y, x)[2 - c]);
    EXPECT_EQ(m->base_color_texture.wrap_u, TextureWrap::kRepeat);
    EXPECT_EQ(m->base_color_texture.wrap_v, TextureWrap::kClampToEdge);
    ASSERT_EQ(m->animations.size(), 1u);
    EXPECT_EQ(m->animations[0].name, "wave");
    EXPECT_EQ(m->animations[0].channels.size(), 3u);
    EXPECT_DOUBLE_EQ(m->animations[0].duration_s, 2.0);
  }
}

TEST_F(GltfSkinTest, RestAndBindPosesPutTheJointsWhereTheRigWasBuilt) {
  const TestRig rig;
  const GltfSkinModel m = LoadGltfSkin(Write(rig, "rig.glb")).value();
  const std::vector<Eigen::Affine3d> rest = SceneFromNode(m, RestTransforms(m));
  const std::vector<Eigen::Affine3d> bind = SceneFromNode(m, BindTransforms(m));
  for (size_t j = 0; j < rig.joints.size(); ++j) {
    const int n = TestRig::Node(static_cast<int>(j));
    EXPECT_LT((rest[n].translation() - rig.joints[j].scene).norm(), 1e-6) << rig.joints[j].name;
    EXPECT_LT((bind[n].matrix() - rest[n].matrix()).cwiseAbs().maxCoeff(), 1e-6)
        << rig.joints[j].name;
  }
}

TEST_F(GltfSkinTest, AMatrixNodeReadsAsItsTranslationRotationAndScale) {
  TestRig rig;
  const Eigen::Affine3d a(test::ArmatureRotation());
  rig.json["nodes"][0].erase("rotation");
  rig.json["nodes"][0]["matrix"] = nlohmann::json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) rig.json["nodes"][0]["matrix"].push_back(a.matrix()(r, c));
  const GltfSkinModel m = LoadGltfSkin(Write(rig, "matrix.gltf")).value();
  EXPECT_LT(QuaternionDistance(m.nodes[0].rest.rotation, test::ArmatureRotation()), 1e-9);
  EXPECT_LT(m.nodes[0].rest.translation.norm(), 1e-12);
  EXPECT_LT((m.nodes[0].rest.scale - Eigen::Vector3d::Ones()).norm(), 1e-12);
}

TEST_F(GltfSkinTest, AnimationAtKeyTimesGivesTheKeysAndSlerpsMidway) {
  const TestRig rig;
  const GltfSkinModel m = LoadGltfSkin(Write(rig, "rig.glb")).value();
  const int forearm = TestRig::Node(rig.JointIndex("LeftForeArm"));
  const int hips = TestRig::Node(0);
  const int leg = TestRig::Node(rig.JointIndex("LeftLeg"));
  for (int k = 0; k < 3; ++k) {
    const std::vector<NodeTransform> t = SampleAnimation(m, 0, k, /*loop=*/false);
    EXPECT_LT(QuaternionDistance(t[forearm].rotation, rig.forearm_keys[k]), 1e-6) << k;
    EXPECT_LT((t[hips].translation - rig.hips_keys[k]).norm(), 1e-6) << k;
    EXPECT_LT((t[leg].scale - rig.leg_scale_keys[k]).norm(), 1e-6) << k;
  }
  // Keys 0 and 1 turn by 0 and 0.6 rad about the same axis: midway is 0.3 rad (slerp).
  const std::vector<NodeTransform> mid = SampleAnimation(m, 0, 0.5, false);
  const Eigen::Quaterniond expected =
      rig.forearm_keys[0] * Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  EXPECT_LT(QuaternionDistance(mid[forearm].rotation, expected), 1e-6);
  EXPECT_LT((mid[hips].translation - rig.hips_keys[0]).norm(), 1e-6);  // STEP holds key 0
  EXPECT_NEAR(mid[leg].scale.x(), 1.05, 1e-6);                         // LINEAR
  // Nodes without a channel keep their rest transform.
  const int head = TestRig::Node(rig.JointIndex("Head"));
  EXPECT_LT((mid[head].translation - m.nodes[head].rest.translation).norm(), 1e-15);
  // Looping wraps by the duration (2 s); without looping the last key holds.
  const std::vector<NodeTransform> looped = SampleAnimation(m, 0, 2.5, true);
  EXPECT_LT(QuaternionDistance(looped[forearm].rotation, expected), 1e-6);
  const std::vector<NodeTransform> held = SampleAnimation(m, 0, 7.0, false);
  EXPECT_LT(QuaternionDistance(held[forearm].rotation, rig.forearm_keys[2]), 1e-6);
  EXPECT_THROW(SampleAnimation(m, 1, 0.0), CheckError);
}

TEST_F(GltfSkinTest, AnimationBeforeTheFirstKeyHoldsTheFirstValue) {
  TestRigOptions o;
  o.key_times = {0.5f, 1.0f, 2.0f};
  const TestRig rig(o);
  const GltfSkinModel m = LoadGltfSkin(Write(rig, "late.glb")).value();
  const int forearm = TestRig::Node(rig.JointIndex("LeftForeArm"));
  EXPECT_LT(QuaternionDistance(SampleAnimation(m, 0, 0.1)[forearm].rotation, rig.forearm_keys[0]),
            1e-6);
}

TEST_F(GltfSkinTest, BaseColourIsBilinearWithTheSamplersWrapModes) {
  const TestRig rig;
  const GltfSkinModel m = LoadGltfSkin(Write(rig, "rig.glb")).value();
  const auto texel = [&](int x, int y) -> Eigen::Vector3d {
    const cv::Vec3b c = rig.texture.at<cv::Vec3b>(y, x);
    return Eigen::Vector3d(c[2], c[1], c[0]) / 255.0;
  };
  // Texel centres at (k + 0.5) / 4.
  EXPECT_LT((SampleBaseColor(m, {1.5 / 4, 2.5 / 4}) - texel(1, 2)).norm(), 1e-12);
  EXPECT_LT((SampleBaseColor(m, {2.0 / 4, 2.5 / 4}) - 0.5 * (texel(1, 2) + texel(2, 2))).norm(),
            1e-12);
  // u repeats: u = 1 + 0.5/4 is texel column 0; between the last and the first column the
  // colour blends across the seam.
  EXPECT_LT((SampleBaseColor(m, {1 + 0.5 / 4, 0.5 / 4}) - texel(0, 0)).norm(), 1e-12);
  EXPECT_LT((SampleBaseColor(m, {0.0, 0.5 / 4}) - 0.5 * (texel(3, 0) + texel(0, 0))).norm(), 1e-12);
  // v clamps to the edge texel.
  EXPECT_LT((SampleBaseColor(m, {0.5 / 4, -0.7}) - texel(0, 0)).norm(), 1e-12);
  EXPECT_LT((SampleBaseColor(m, {0.5 / 4, 1.9}) - texel(0, 3)).norm(), 1e-12);
}

TEST_F(GltfSkinTest, RealCesiumManLoads) {
  if (!std::filesystem::exists(kCesiumMan)) GTEST_SKIP() << kCesiumMan << " is absent";
  const Expected<GltfSkinModel> m = LoadGltfSkin(kCesiumMan);
  ASSERT_TRUE(m.ok()) << m.error().message;
  // ../shared/data/README.md: 3,273 vertices, one skin of 19 joints, a walk animation,
  // an embedded texture.
  EXPECT_EQ(m->vertices.size(), 3273u);
  EXPECT_EQ(m->joint_nodes.size(), 19u);
  EXPECT_FALSE(m->base_color_texture.image.empty());
  ASSERT_EQ(m->animations.size(), 1u);
  EXPECT_GT(m->animations[0].duration_s, 0.5);
  EXPECT_TRUE(m->warnings.empty());
  // The root node Z_UP rotates the z-up armature to y-up: at rest the head is high in y.
  const std::vector<Eigen::Affine3d> rest = SceneFromNode(*m, RestTransforms(*m));
  double top = -1e9;
  for (int n : m->joint_nodes) top = std::max(top, rest[n].translation().y());
  EXPECT_GT(top, 1.0);
}

// --- Bad input, one test each. ---

TEST_F(GltfSkinTest, MissingFileIsNotFound) {
  const Expected<GltfSkinModel> m = LoadGltfSkin((dir_ / "nothing.glb").string());
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.error().code, "not_found");
}

TEST_F(GltfSkinTest, AFileThatIsNotGltfIsCorrupt) {
  std::ofstream(dir_ / "hello.glb") << "hello, this is not glTF";
  const Expected<GltfSkinModel> m = LoadGltfSkin((dir_ / "hello.glb").string());
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.error().code, "corrupt");
  EXPECT_NE(m.error().message.find("not a readable glTF"), std::string::npos) << m.error().message;
}

TEST_F(GltfSkinTest, ATruncatedGlbIsCorrupt) {
  std::vector<uint8_t> b = TestRig().GlbBytes();
  b.resize(b.size() / 2);
  std::ofstream(dir_ / "cut.glb", std::ios::binary)
      .write(reinterpret_cast<const char*>(b.data()), b.size());
  const Expected<GltfSkinModel> m = LoadGltfSkin((dir_ / "cut.glb").string());
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.error().code, "corrupt") << m.error().message;
}

TEST_F(GltfSkinTest, NoSkinIsUnsupported) {
  ExpectError([](TestRig& r) { r.json["nodes"][1].erase("skin"); }, "unsupported",
              "no skinned mesh");
}

TEST_F(GltfSkinTest, NoMeshIsUnsupported) {
  ExpectError(
      [](TestRig& r) {
        r.json["nodes"][1].erase("mesh");
        r.json.erase("meshes");
      },
      "unsupported", "no mesh");
}

TEST_F(GltfSkinTest, NoTextureFallsBackToTheBaseColourFactorAndSaysSo) {
  TestRigOptions o;
  o.texture = false;
  const GltfSkinModel m = LoadGltfSkin(Write(TestRig(o), "plain.gltf")).value();
  EXPECT_TRUE(m.base_color_texture.image.empty());
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("base colour factor"), std::string::npos) << m.warnings[0];
  EXPECT_LT((SampleBaseColor(m, {0.3, 0.6}) - Eigen::Vector3d(0.8, 0.4, 0.2)).norm(), 1e-12);
}

TEST_F(GltfSkinTest, AnAccessorIndexOutOfRangeIsCorrupt) {
  ExpectError(
      [](TestRig& r) { r.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 999; },
      "corrupt", "accessor 999");
}

TEST_F(GltfSkinTest, AnAccessorRunningPastItsBufferViewIsCorrupt) {
  ExpectError(
      [](TestRig& r) {
        const int a = r.json["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"];
        r.json["accessors"][a]["byteOffset"] = 64;
      },
      "corrupt", "runs past the end");
}

TEST_F(GltfSkinTest, WeightsThatDoNotSumToOneAreNormalisedAndSaidSo) {
  TestRigOptions o;
  o.weight_scale = 0.8;
  const TestRig rig(o);
  const GltfSkinModel m = LoadGltfSkin(Write(rig, "light.gltf")).value();
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("normalised"), std::string::npos) << m.warnings[0];
  for (size_t i = 0; i < m.vertices.size(); ++i) {
    EXPECT_NEAR(m.vertices[i].weights.sum(), 1.0, 1e-12);
    EXPECT_NEAR(m.vertices[i].weights[0], rig.vertex_weights[i][0], 1e-6);  // ratios kept
  }
}

TEST_F(GltfSkinTest, AllWeightsZeroIsCorrupt) {
  TestRigOptions o;
  o.weight_scale = 0;
  ExpectError([](TestRig&) {}, "corrupt", "all skin weights zero", o);
}

TEST_F(GltfSkinTest, AJointIndexBeyondTheSkinIsCorrupt) {
  TestRigOptions o;
  o.bad_joint_index = 40;
  ExpectError([](TestRig&) {}, "corrupt", "refers to joint 40", o);
}

TEST_F(GltfSkinTest, AVertexIndexBeyondThePrimitiveIsCorrupt) {
  ExpectError(
      [](TestRig& r) {
        const int a = r.json["meshes"][0]["primitives"][0]["indices"];
        const int view = r.json["accessors"][a]["bufferView"];
        const size_t offset = r.json["bufferViews"][view]["byteOffset"];
        r.bin[offset] = 0xff;  // first index -> 0x..ff, beyond the vertex count
        r.bin[offset + 1] = 0x7f;
      },
      "corrupt", "index 0 is");
}

TEST_F(GltfSkinTest, ANodeCycleIsCorrupt) {
  ExpectError([](TestRig& r) { r.json["nodes"][TestRig::Node(3)]["children"] = {0}; }, "corrupt",
              "cycle");
}

TEST_F(GltfSkinTest, ANodeWithTwoParentsIsCorrupt) {
  ExpectError([](TestRig& r) { r.json["nodes"][TestRig::Node(3)]["children"] = {1}; }, "corrupt",
              "more than one parent");
}

TEST_F(GltfSkinTest, AShearedNodeMatrixIsCorrupt) {
  ExpectError(
      [](TestRig& r) {
        r.json["nodes"][0].erase("rotation");
        r.json["nodes"][0]["matrix"] = {1, 0, 0, 0, 0.5, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
      },
      "corrupt", "shears");
}

TEST_F(GltfSkinTest, CubicSplineAnimationIsUnsupported) {
  TestRigOptions o;
  o.interpolation = "CUBICSPLINE";
  ExpectError([](TestRig&) {}, "unsupported", "CUBICSPLINE", o);
}

TEST_F(GltfSkinTest, DecreasingKeyTimesAreCorrupt) {
  TestRigOptions o;
  o.key_times = {0.0f, 2.0f, 1.0f};
  ExpectError([](TestRig&) {}, "corrupt", "key times that decrease", o);
}

TEST_F(GltfSkinTest, PointsAreUnsupported) {
  ExpectError([](TestRig& r) { r.json["meshes"][0]["primitives"][0]["mode"] = 0; }, "unsupported",
              "only triangles");
}

TEST_F(GltfSkinTest, InverseBindMatricesMustMatchTheJoints) {
  ExpectError(
      [](TestRig& r) {
        const int a = r.json["skins"][0]["inverseBindMatrices"];
        r.json["accessors"][a]["count"] = 15;
      },
      "corrupt", "16 joints but 15 inverse bind matrices");
}

TEST_F(GltfSkinTest, GltfVersionOneIsUnsupported) {
  ExpectError([](TestRig& r) { r.json["asset"]["version"] = "1.0"; }, "unsupported",
              "only glTF 2.x");
}

TEST_F(GltfSkinTest, TwoMaterialsOnTheSkinnedMeshAreUnsupported) {
  ExpectError(
      [](TestRig& r) {
        nlohmann::json p = r.json["meshes"][0]["primitives"][0];
        p["material"] = 1;
        r.json["meshes"][0]["primitives"].push_back(p);
        r.json["materials"].push_back(r.json["materials"][0]);
      },
      "unsupported", "different materials");
}

TEST_F(GltfSkinTest, MissingNormalsAreComputedFacingOutwardsAndSaidSo) {
  TestRigOptions o;
  o.normals = false;
  const TestRig rig(o);
  const GltfSkinModel m = LoadGltfSkin(Write(rig, "flat.gltf")).value();
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("normals"), std::string::npos) << m.warnings[0];
  // Every vertex is a corner of an axis-aligned box, in one to two triangles of each of the
  // three faces that meet there: its area-weighted normal is a positive combination of those
  // faces' outward axes, so each component has the sign of the corner's direction from the
  // box centre (rig.normals).
  for (size_t i = 0; i < m.vertices.size(); ++i) {
    EXPECT_NEAR(m.vertices[i].normal.norm(), 1.0, 1e-12);
    EXPECT_GT(m.vertices[i].normal.cwiseProduct(rig.normals[i]).minCoeff(), 0) << i;
  }
}

TEST_F(GltfSkinTest, SparseAccessorsAreUnsupported) {
  ExpectError(
      [](TestRig& r) {
        const int a = r.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
        const std::vector<uint16_t> idx = {0};
        const std::vector<float> val = {0, 0, 0};
        const int iv = r.AddView(idx.data(), 2);
        const int vv = r.AddView(val.data(), 12);
        r.json["accessors"][a]["sparse"] = {
            {"count", 1},
            {"indices", {{"bufferView", iv}, {"componentType", 5123}}},
            {"values", {{"bufferView", vv}}}};
      },
      "unsupported", "sparse");
}

}  // namespace
}  // namespace reenact::capture
