#pragma once
// A small skinned humanoid written as glTF 2.0 by the tests themselves (.gltf with a data-URI
// buffer, or .glb), with its ground truth known by construction:
//  - nodes: 0 "Armature" (root; rotates its z-up frame to glTF's y-up, like CesiumMan's
//    root), 1 "Body" (the skinned mesh, a child of the Armature, so its bind space is the
//    z-up armature frame), 2.. the 16 joints below (joint j is node j + 2);
//  - joints named like Mixamo's rig (so GltfJointsByName maps them), each with a rest
//    rotation of its own (so local transforms are not trivial);
//  - per bone a box of 8 vertices, all weighted to that bone's joint, plus at each elbow and
//    knee 4 vertices weighted 0.6 / 0.4 between the limb's two joints;
//  - a 4x4 texture, and one animation (LeftForeArm rotation, Hips translation, LeftLeg
//    scale).
// Scene frame (glTF): y up, +z the front, +x the left; the armature frame a maps to the
// scene as s = (a.x, a.z, -a.y).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

namespace reenact::capture::test {

struct RigJoint {
  std::string name;
  int parent;                   // joint index, -1 for the root joint
  Eigen::Vector3d scene;        // bind position in the scene frame
  Eigen::Quaterniond rotation;  // bind rotation in the armature frame
};

struct TestRigOptions {
  std::string spine_name = "Spine";  // "SpineLower" is not a torso name: torso derived
  bool texture = true;
  bool normals = true;
  double weight_scale = 1.0;  // multiplies every stored weight
  int bad_joint_index = -1;   // >= 0: vertex 0's first joint index
  std::vector<float> key_times = {0.0f, 1.0f, 2.0f};
  std::string interpolation = "LINEAR";
};

inline Eigen::Vector3d ArmatureFromScene(const Eigen::Vector3d& s) {
  return {s.x(), -s.z(), s.y()};
}
inline Eigen::Vector3d SceneFromArmature(const Eigen::Vector3d& a) {
  return {a.x(), a.z(), -a.y()};
}
// The Armature node's rotation: -90 degrees about x (armature z-up -> scene y-up).
inline Eigen::Quaterniond ArmatureRotation() {
  return Eigen::Quaterniond(Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitX()));
}

inline std::string Base64(const std::vector<uint8_t>& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const uint32_t v = (in[i] << 16) | (in[i + 1] << 8) | in[i + 2];
    for (int s = 18; s >= 0; s -= 6) out += k[(v >> s) & 63];
  }
  if (i + 1 == in.size()) {
    const uint32_t v = in[i] << 16;
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == in.size()) {
    const uint32_t v = (in[i] << 16) | (in[i + 1] << 8);
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += k[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

class TestRig {
 public:
  explicit TestRig(const TestRigOptions& o = {}) : options(o) { Build(); }

  TestRigOptions options;
  std::vector<RigJoint> joints;
  // Mesh ground truth, bind space (armature frame).
  std::vector<Eigen::Vector3d> positions;
  std::vector<Eigen::Vector3d> normals;
  std::vector<Eigen::Vector2d> uvs;
  std::vector<Eigen::Vector4i> vertex_joints;
  std::vector<Eigen::Vector4d> vertex_weights;
  std::vector<Eigen::Vector3i> triangles;
  cv::Mat texture;  // 4x4 BGR
  // The animation's keys.
  std::vector<Eigen::Quaterniond> forearm_keys;  // LeftForeArm local rotation
  std::vector<Eigen::Vector3d> hips_keys;        // Hips local translation (STEP in tests)
  std::vector<Eigen::Vector3d> leg_scale_keys;   // LeftLeg local scale

  nlohmann::json json;
  std::vector<uint8_t> bin;

  static int Node(int joint) { return joint + 2; }
  int JointIndex(const std::string& name) const {
    for (size_t j = 0; j < joints.size(); ++j)
      if (joints[j].name == name) return static_cast<int>(j);
    return -1;
  }

  // The .gltf text with the buffer as a data URI.
  std::string GltfText() const {
    nlohmann::json j = json;
    j["buffers"] = {{{"byteLength", bin.size()},
                     {"uri", "data:application/octet-stream;base64," + Base64(bin)}}};
    return j.dump();
  }
  std::vector<uint8_t> GlbBytes() const {
    nlohmann::json j = json;
    j["buffers"] = {{{"byteLength", bin.size()}}};
    std::string text = j.dump();
    while (text.size() % 4 != 0) text += ' ';
    std::vector<uint8_t> b = bin;
    while (b.size() % 4 != 0) b.push_back(0);
    std::vector<uint8_t> out;
    const auto u32 = [&](uint32_t v) {
      for (int k = 0; k < 4; ++k) out.push_back(static_cast<uint8_t>(v >> (8 * k)));
    };
    out.insert(out.end(), {'g', 'l', 'T', 'F'});
    u32(2);
    u32(static_cast<uint32_t>(12 + 8 + text.size() + 8 + b.size()));
    u32(static_cast<uint32_t>(text.size()));
    out.insert(out.end(), {'J', 'S', 'O', 'N'});
    out.insert(out.end(), text.begin(), text.end());
    u32(static_cast<uint32_t>(b.size()));
    out.insert(out.end(), {'B', 'I', 'N', 0});
    out.insert(out.end(), b.begin(), b.end());
    return out;
  }
  void WriteGltf(const std::filesystem::path& p) const { std::ofstream(p) << GltfText(); }
  void WriteGlb(const std::filesystem::path& p) const {
    const std::vector<uint8_t> b = GlbBytes();
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), b.size());
  }

  // Appends raw data as a new buffer view (4-byte aligned) and returns its index.
  int AddView(const void* data, size_t bytes) {
    while (bin.size() % 4 != 0) bin.push_back(0);
    const size_t offset = bin.size();
    bin.resize(offset + bytes);
    std::memcpy(bin.data() + offset, data, bytes);
    json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
    return static_cast<int>(json["bufferViews"].size()) - 1;
  }
  template <typename T>
  int AddAccessor(const std::vector<T>& values, int component_type, const std::string& type,
                  size_t count) {
    const int view = AddView(values.data(), values.size() * sizeof(T));
    json["accessors"].push_back({{"bufferView", view},
                                 {"componentType", component_type},
                                 {"count", count},
                                 {"type", type}});
    return static_cast<int>(json["accessors"].size()) - 1;
  }

 private:
  void Build() {
    using Eigen::AngleAxisd;
    using Eigen::Quaterniond;
    using Eigen::Vector3d;
    const auto q = [](double deg, const Vector3d& axis) {
      return Quaterniond(AngleAxisd(deg * std::numbers::pi / 180, axis.normalized()));
    };
    joints = {
        {"Hips", -1, {0, 1.0, 0}, q(10, {0, 0, 1})},
        {options.spine_name, 0, {0, 1.25, -0.02}, q(-15, {1, 0, 0})},
        {"Neck", 1, {0, 1.5, 0}, q(5, {0, 1, 0})},
        {"Head", 2, {0, 1.6, 0.01}, q(0, {0, 0, 1})},
        {"LeftArm", 1, {0.2, 1.45, 0}, q(30, {1, 1, 0})},
        {"LeftForeArm", 4, {0.5, 1.45, 0}, q(30, {1, 0, 0})},
        {"LeftHand", 5, {0.75, 1.45, 0}, q(-20, {0, 1, 1})},
        {"RightArm", 1, {-0.2, 1.45, 0}, q(-30, {1, 1, 0})},
        {"RightForeArm", 7, {-0.5, 1.45, 0}, q(40, {0, 0, 1})},
        {"RightHand", 8, {-0.75, 1.45, 0}, q(0, {0, 0, 1})},
        {"LeftUpLeg", 0, {0.1, 0.92, 0.02}, q(180, {0, 1, 0})},
        {"LeftLeg", 10, {0.1, 0.5, 0.03}, q(170, {0, 1, 0.1})},
        {"LeftFoot", 11, {0.1, 0.08, 0}, q(25, {1, 0, 0})},
        {"RightUpLeg", 0, {-0.1, 0.92, 0.02}, q(180, {0, 1, 0})},
        {"RightLeg", 13, {-0.1, 0.5, 0.03}, q(0, {0, 0, 1})},
        {"RightFoot", 14, {-0.1, 0.08, 0}, q(0, {0, 0, 1})},
    };
    BuildMesh();
    BuildJson();
  }

  void BuildMesh() {
    using Eigen::Vector3d;
    // Per joint: a box (in the scene frame) around the segment to its first child, or a
    // short end piece; the head a cube above it; the feet down to the floor (y = 0).
    for (size_t j = 0; j < joints.size(); ++j) {
      Vector3d lo, hi;
      const Vector3d p = joints[j].scene;
      int child = -1;
      for (size_t c = 0; c < joints.size(); ++c)
        if (joints[c].parent == static_cast<int>(j)) {
          child = static_cast<int>(c);
          break;
        }
      if (joints[j].name == "Head") {
        lo = p + Vector3d(-0.09, -0.02, -0.1);
        hi = p + Vector3d(0.09, 0.22, 0.1);
      } else if (joints[j].name.find("Foot") != std::string::npos) {
        lo = Vector3d(p.x() - 0.05, 0.0, -0.05);
        hi = Vector3d(p.x() + 0.05, p.y(), 0.15);
      } else if (joints[j].name.find("Hand") != std::string::npos) {
        const double s = p.x() > 0 ? 1 : -1;
        lo = p + Vector3d(s > 0 ? 0.0 : -0.15, -0.04, -0.04);
        hi = p + Vector3d(s > 0 ? 0.15 : 0.0, 0.04, 0.04);
      } else if (j == 0) {  // pelvis
        lo = p + Vector3d(-0.15, -0.1, -0.08);
        hi = p + Vector3d(0.15, 0.2, 0.08);
      } else {
        const Vector3d c = joints[child].scene;
        lo = p.cwiseMin(c) - Vector3d::Constant(0.045);
        hi = p.cwiseMax(c) + Vector3d::Constant(0.045);
        if (joints[j].name == options.spine_name) {
          lo = p.cwiseMin(c) - Vector3d(0.14, -0.01, 0.08);  // starts above the torso joint
          hi = p.cwiseMax(c) + Vector3d(0.14, 0.0, 0.08);
        }
      }
      AddBox(lo, hi, Eigen::Vector4i(static_cast<int>(j), 0, 0, 0), Eigen::Vector4d(1, 0, 0, 0));
    }
    // Blend vertices at the elbows and knees: 0.6 on the distal joint, 0.4 on the proximal.
    for (const char* name : {"LeftForeArm", "RightForeArm", "LeftLeg", "RightLeg"}) {
      const int j = JointIndex(name);
      const Vector3d p = joints[j].scene;
      const Eigen::Vector4i jj(j, joints[j].parent, 0, 0);
      const Eigen::Vector4d ww(0.6, 0.4, 0, 0);
      AddBox(p - Vector3d::Constant(0.05), p + Vector3d::Constant(0.05), jj, ww);
    }
    // 4x4 texture of distinct colours.
    texture = cv::Mat(4, 4, CV_8UC3);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        texture.at<cv::Vec3b>(y, x) =
            cv::Vec3b(static_cast<uint8_t>(40 * x + 20), static_cast<uint8_t>(60 * y + 10),
                      static_cast<uint8_t>(200 - 30 * x));
  }

  // Appends a box (scene-frame corners) as 8 vertices and 12 outward triangles.
  void AddBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Eigen::Vector4i& j,
              const Eigen::Vector4d& w) {
    const int base = static_cast<int>(positions.size());
    const Eigen::Vector3d centre = 0.5 * (lo + hi);
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d s((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(),
                              (k & 4) ? hi.z() : lo.z());
      positions.push_back(ArmatureFromScene(s));
      normals.push_back(ArmatureFromScene((s - centre).normalized()));
      uvs.emplace_back(((k & 3) + 0.5) / 4.0, ((k >> 1) + 0.5) / 4.0);
      vertex_joints.push_back(j);
      vertex_weights.push_back(w);
    }
    const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                             {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    for (const auto& f : faces) {
      for (const Eigen::Vector3i& t :
           {Eigen::Vector3i(f[0], f[1], f[2]), Eigen::Vector3i(f[0], f[2], f[3])}) {
        Eigen::Vector3i tri = t + Eigen::Vector3i::Constant(base);
        const Eigen::Vector3d a = positions[tri[0]], b = positions[tri[1]], c = positions[tri[2]];
        const Eigen::Vector3d n = (b - a).cross(c - a);
        const Eigen::Vector3d mid = (a + b + c) / 3.0 - ArmatureFromScene(centre);
        if (n.dot(mid) < 0) std::swap(tri[1], tri[2]);
        triangles.push_back(tri);
      }
    }
  }

  void BuildJson() {
    using Eigen::Vector3d;
    json = nlohmann::json::object();
    json["asset"] = {{"version", "2.0"}, {"generator", "reenact unit test"}};
    json["scene"] = 0;
    json["scenes"] = {{{"nodes", {0}}}};
    json["accessors"] = nlohmann::json::array();
    json["bufferViews"] = nlohmann::json::array();
    const Eigen::Quaterniond ar = ArmatureRotation();
    nlohmann::json nodes = nlohmann::json::array();
    nodes.push_back({{"name", "Armature"},
                     {"rotation", {ar.x(), ar.y(), ar.z(), ar.w()}},
                     {"children", {1, Node(0)}}});
    nodes.push_back({{"name", "Body"}, {"mesh", 0}, {"skin", 0}});
    for (size_t j = 0; j < joints.size(); ++j) {
      const RigJoint& jt = joints[j];
      const Vector3d a = ArmatureFromScene(jt.scene);
      Vector3d t = a;
      Eigen::Quaterniond r = jt.rotation;
      if (jt.parent >= 0) {
        const RigJoint& p = joints[jt.parent];
        t = p.rotation.conjugate() * (a - ArmatureFromScene(p.scene));
        r = p.rotation.conjugate() * jt.rotation;
      }
      nlohmann::json n = {{"name", jt.name},
                          {"translation", {t.x(), t.y(), t.z()}},
                          {"rotation", {r.x(), r.y(), r.z(), r.w()}}};
      nlohmann::json children = nlohmann::json::array();
      for (size_t c = 0; c < joints.size(); ++c)
        if (joints[c].parent == static_cast<int>(j)) children.push_back(Node(static_cast<int>(c)));
      if (!children.empty()) n["children"] = children;
      nodes.push_back(n);
    }
    json["nodes"] = nodes;

    // Mesh.
    std::vector<float> pos, nor, uv, wts, ibm;
    std::vector<uint16_t> jnt, idx;
    for (size_t i = 0; i < positions.size(); ++i) {
      for (int k = 0; k < 3; ++k) pos.push_back(static_cast<float>(positions[i][k]));
      for (int k = 0; k < 3; ++k) nor.push_back(static_cast<float>(normals[i][k]));
      for (int k = 0; k < 2; ++k) uv.push_back(static_cast<float>(uvs[i][k]));
      for (int k = 0; k < 4; ++k) {
        jnt.push_back(static_cast<uint16_t>(vertex_joints[i][k]));
        wts.push_back(static_cast<float>(vertex_weights[i][k] * options.weight_scale));
      }
    }
    if (options.bad_joint_index >= 0) jnt[0] = static_cast<uint16_t>(options.bad_joint_index);
    for (const Eigen::Vector3i& t : triangles)
      for (int k = 0; k < 3; ++k) idx.push_back(static_cast<uint16_t>(t[k]));
    const size_t n = positions.size();
    nlohmann::json attributes;
    attributes["POSITION"] = AddAccessor(pos, 5126, "VEC3", n);
    if (options.normals) attributes["NORMAL"] = AddAccessor(nor, 5126, "VEC3", n);
    attributes["TEXCOORD_0"] = AddAccessor(uv, 5126, "VEC2", n);
    attributes["JOINTS_0"] = AddAccessor(jnt, 5123, "VEC4", n);
    attributes["WEIGHTS_0"] = AddAccessor(wts, 5126, "VEC4", n);
    const int indices = AddAccessor(idx, 5123, "SCALAR", idx.size());
    json["meshes"] = {
        {{"name", "Body"},
         {"primitives", {{{"attributes", attributes}, {"indices", indices}, {"material", 0}}}}}};
    nlohmann::json material = {{"name", "skin"},
                               {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}}}};
    if (options.texture) {
      std::vector<uint8_t> png;
      cv::imencode(".png", texture, png);
      const int view = AddView(png.data(), png.size());
      json["images"] = {{{"bufferView", view}, {"mimeType", "image/png"}}};
      json["samplers"] = {{{"wrapS", 10497}, {"wrapT", 33071}}};
      json["textures"] = {{{"source", 0}, {"sampler", 0}}};
      material["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    } else {
      material["pbrMetallicRoughness"]["baseColorFactor"] = {0.8, 0.4, 0.2, 1.0};
    }
    json["materials"] = {material};

    // Skin: inverse bind matrices = (T(a_j) R_j)^-1 in the armature (= bind) frame.
    for (const RigJoint& jt : joints) {
      Eigen::Affine3d bind = Eigen::Affine3d::Identity();
      bind.translate(ArmatureFromScene(jt.scene));
      bind.rotate(jt.rotation);
      const Eigen::Matrix4d m = bind.inverse().matrix();
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) ibm.push_back(static_cast<float>(m(r, c)));
    }
    nlohmann::json joint_nodes = nlohmann::json::array();
    for (size_t j = 0; j < joints.size(); ++j) joint_nodes.push_back(Node(static_cast<int>(j)));
    json["skins"] = {{{"joints", joint_nodes},
                      {"inverseBindMatrices", AddAccessor(ibm, 5126, "MAT4", joints.size())}}};

    // Animation.
    const int forearm = JointIndex("LeftForeArm"), hips = 0, leg = JointIndex("LeftLeg");
    const Eigen::Quaterniond rest_forearm =
        joints[joints[forearm].parent].rotation.conjugate() * joints[forearm].rotation;
    std::vector<float> times = options.key_times, rot, tra, scl;
    for (size_t k = 0; k < times.size(); ++k) {
      const Eigen::Quaterniond r =
          rest_forearm * Eigen::Quaterniond(Eigen::AngleAxisd(0.6 * k, Vector3d(0, 0, 1)));
      forearm_keys.push_back(r);
      rot.insert(rot.end(), {static_cast<float>(r.x()), static_cast<float>(r.y()),
                             static_cast<float>(r.z()), static_cast<float>(r.w())});
      const Vector3d h = ArmatureFromScene(joints[hips].scene) + Vector3d(0.01 * k, 0, 0.02 * k);
      hips_keys.push_back(h);
      tra.insert(tra.end(),
                 {static_cast<float>(h.x()), static_cast<float>(h.y()), static_cast<float>(h.z())});
      const Vector3d s(1.0 + 0.1 * k, 1.0, 1.0);
      leg_scale_keys.push_back(s);
      scl.insert(scl.end(), {static_cast<float>(s.x()), 1.0f, 1.0f});
    }
    const int input = AddAccessor(times, 5126, "SCALAR", times.size());
    const int rot_out = AddAccessor(rot, 5126, "VEC4", times.size());
    const int tra_out = AddAccessor(tra, 5126, "VEC3", times.size());
    const int scl_out = AddAccessor(scl, 5126, "VEC3", times.size());
    json["animations"] = {
        {{"name", "wave"},
         {"samplers",
          {{{"input", input}, {"output", rot_out}, {"interpolation", options.interpolation}},
           {{"input", input}, {"output", tra_out}, {"interpolation", "STEP"}},
           {{"input", input}, {"output", scl_out}, {"interpolation", "LINEAR"}}}},
         {"channels",
          {{{"sampler", 0}, {"target", {{"node", Node(forearm)}, {"path", "rotation"}}}},
           {{"sampler", 1}, {"target", {{"node", Node(hips)}, {"path", "translation"}}}},
           {{"sampler", 2}, {"target", {{"node", Node(leg)}, {"path", "scale"}}}}}}}};
  }
};

}  // namespace reenact::capture::test
