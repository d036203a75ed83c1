#include "synthetic/skinned_body.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "common/error/check.h"
#include "common/geometry/rotation.h"
#include "common/skeleton/joint_maps.h"
#include "synthetic/room.h"

namespace reenact::capture {

using Eigen::Matrix3d;
using Eigen::Vector3d;

struct SkinnedBody::Data {
  GltfSkinModel model;
  double height_m = 0;
  double scale = 1;
  Eigen::Affine3d body_from_scene = Eigen::Affine3d::Identity();
  std::vector<NodeTransform> bind_local;
  std::array<int, kJointCount> joint_node{};  // -1: torso derived as mean(neck, waist)
  std::array<Vector3d, kJointCount> joint_offset{};
  int spine_pivot = -1;  // derived torso: the node below the waist on the path to the neck
  std::vector<BodyPart> joint_part, vertex_part;
  // The torso split (header: body-part labels): bind-space (scene frame) spine joints, the
  // waist and the waist -> neck line, and the torso joint's fraction along it.
  std::vector<bool> joint_on_spine;
  Vector3d split_waist = Vector3d::Zero(), split_spine = Vector3d::UnitZ();
  double split_torso_t = 0.5;
  std::vector<Vector3d> bind_vertices;  // scene frame

  // The part of a surface point whose dominant skin joint is `joint` at bind position p.
  BodyPart PartAt(int joint, const Vector3d& p) const {
    if (!joint_on_spine[joint]) return joint_part[joint];
    const double t = (p - split_waist).dot(split_spine) / split_spine.squaredNorm();
    return t > split_torso_t ? BodyPart::kUpperTorso : BodyPart::kLowerTorso;
  }
  // The part of the point of triangle `triangle` at bind position p (header: body-part labels).
  BodyPart PartOfSurfacePoint(int triangle, const Vector3d& p) const;
};

namespace {

// The part a skin joint mapped to our joint j carries: the cylinder along which the skin
// that j moves lies, from j to its child (hands with the forearms, feet with the shins).
BodyPart PartOfJoint(Joint j) {
  switch (j) {
    case Joint::kHead:
    case Joint::kNeck:
      return BodyPart::kHead;
    case Joint::kTorso:
      return BodyPart::kUpperTorso;
    case Joint::kWaist:
      return BodyPart::kLowerTorso;
    case Joint::kLeftShoulder:
      return BodyPart::kLeftUpperArm;
    case Joint::kLeftElbow:
    case Joint::kLeftHand:
      return BodyPart::kLeftForearm;
    case Joint::kRightShoulder:
      return BodyPart::kRightUpperArm;
    case Joint::kRightElbow:
    case Joint::kRightHand:
      return BodyPart::kRightForearm;
    case Joint::kLeftHip:
      return BodyPart::kLeftThigh;
    case Joint::kLeftKnee:
    case Joint::kLeftFoot:
      return BodyPart::kLeftShin;
    case Joint::kRightHip:
      return BodyPart::kRightThigh;
    case Joint::kRightKnee:
    case Joint::kRightFoot:
      return BodyPart::kRightShin;
  }
  return BodyPart::kLowerTorso;
}

// The bones aligned after the pelvis and the chest: (proximal, distal), parents first.
constexpr std::array<std::pair<Joint, Joint>, 9> kLimbBones = {{
    {Joint::kNeck, Joint::kHead},
    {Joint::kLeftShoulder, Joint::kLeftElbow},
    {Joint::kLeftElbow, Joint::kLeftHand},
    {Joint::kRightShoulder, Joint::kRightElbow},
    {Joint::kRightElbow, Joint::kRightHand},
    {Joint::kLeftHip, Joint::kLeftKnee},
    {Joint::kLeftKnee, Joint::kLeftFoot},
    {Joint::kRightHip, Joint::kRightKnee},
    {Joint::kRightKnee, Joint::kRightFoot},
}};

bool IsDescendant(const GltfSkinModel& m, int node, int ancestor) {
  for (int p = m.nodes[node].parent; p >= 0; p = m.nodes[p].parent)
    if (p == ancestor) return true;
  return false;
}

// The child of `ancestor` on the path down to `node` (precondition: node is a descendant).
int ChildTowards(const GltfSkinModel& m, int ancestor, int node) {
  int n = node;
  while (m.nodes[n].parent != ancestor) n = m.nodes[n].parent;
  return n;
}

// R with R a_from parallel to a_to and, about a_to, R b_from in the half-plane of
// (a_to, b_to). Falls back to the minimal rotation when a b is parallel to its a, and to
// the identity when an a is zero.
Matrix3d TwoVectorRotation(const Vector3d& a_from, const Vector3d& b_from, const Vector3d& a_to,
                           const Vector3d& b_to) {
  const std::optional<Matrix3d> r1 = RotationBetween(a_from, a_to);
  if (!r1) return Matrix3d::Identity();
  const Vector3d axis = a_to.normalized();
  const Vector3d b1 = *r1 * b_from;
  const Vector3d p = b1 - b1.dot(axis) * axis;
  const Vector3d q = b_to - b_to.dot(axis) * axis;
  if (p.norm() < 1e-12 || q.norm() < 1e-12) return *r1;
  const double angle = std::atan2(axis.dot(p.cross(q)), p.dot(q));
  return Eigen::AngleAxisd(angle, axis).toRotationMatrix() * *r1;
}

// The minimal rotation about the point `pivot` that moves `moving` onto the ray from
// `anchor` along `direction` (|moving - pivot| is kept; when the ray misses that sphere,
// onto the ray's point closest to it).
Matrix3d AimAbout(const Vector3d& pivot, const Vector3d& anchor, const Vector3d& moving,
                  const Vector3d& direction) {
  const double r = (moving - pivot).norm();
  if (r < 1e-12 || direction.norm() < 1e-12) return Matrix3d::Identity();
  const Vector3d d = direction.normalized();
  const Vector3d w = anchor - pivot;
  const double b = d.dot(w);
  const double disc = b * b - (w.squaredNorm() - r * r);
  const double lambda = -b + std::sqrt(std::max(disc, 0.0));
  const Vector3d target = anchor + lambda * d;
  return RotationBetween(moving - pivot, target - pivot).value_or(Matrix3d::Identity());
}

Error Unsupported(const GltfSkinModel& m, const std::string& what) {
  return MakeError("unsupported", m.path + ": " + what);
}

}  // namespace

BodyPart SkinnedBody::Data::PartOfSurfacePoint(int triangle, const Vector3d& p) const {
  const Eigen::Vector3i& tri = model.triangles[triangle];
  const Vector3d& a = bind_vertices[tri[0]];
  const Vector3d e1 = bind_vertices[tri[1]] - a, e2 = bind_vertices[tri[2]] - a, q = p - a;
  const double g00 = e1.squaredNorm(), g01 = e1.dot(e2), g11 = e2.squaredNorm();
  const double det = g00 * g11 - g01 * g01;
  std::array<double, 3> l{1, 0, 0};  // a degenerate triangle: its first vertex's weights
  if (std::isfinite(det) && det > 1e-12 * g00 * g11) {
    l[1] = std::max(0.0, (g11 * e1.dot(q) - g01 * e2.dot(q)) / det);
    l[2] = std::max(0.0, (g00 * e2.dot(q) - g01 * e1.dot(q)) / det);
    l[0] = std::max(0.0, 1 - l[1] - l[2]);
    const double sum = l[0] + l[1] + l[2];
    for (double& v : l) v /= sum;
  }
  std::array<std::pair<int, double>, 12> weights{};
  int count = 0;
  Vector3d bind = Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const SkinVertex& v = model.vertices[tri[i]];
    bind += l[i] * bind_vertices[tri[i]];
    for (int k = 0; k < 4; ++k) {
      if (v.weights[k] <= 0) continue;
      int e = 0;
      while (e < count && weights[e].first != v.joints[k]) ++e;
      if (e == count) weights[count++] = {v.joints[k], 0.0};
      weights[e].second += l[i] * v.weights[k];
    }
  }
  std::pair<int, double> best{-1, -1};
  for (int e = 0; e < count; ++e)
    if (weights[e].second > best.second ||
        (weights[e].second == best.second && weights[e].first < best.first))
      best = weights[e];
  return best.first >= 0 ? PartAt(best.first, bind) : vertex_part[tri[0]];
}

void SkinnedBodyOptions::Check() const {
  REENACT_CHECK(std::isfinite(height_m) && height_m >= 0 && height_m < 10,
                "height_m must be 0 (keep the model's) or a height in (0, 10) metres");
}

Eigen::Isometry3d WorldFromBody(const Eigen::Vector2d& root_xy, double yaw) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(yaw - std::numbers::pi / 2, Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = Vector3d(root_xy.x(), root_xy.y(), 0);
  return t;
}

Expected<SkinnedBody> SkinnedBody::Load(const std::string& path,
                                        const SkinnedBodyOptions& options) {
  Expected<GltfSkinModel> model = LoadGltfSkin(path);
  if (!model.ok()) return model.error();
  return Create(std::move(model).value(), options);
}

Expected<SkinnedBody> SkinnedBody::Create(GltfSkinModel model, const SkinnedBodyOptions& options) {
  options.Check();
  const auto invalid = [&](const std::string& what) {
    return MakeError("invalid_argument", model.path + ": inconsistent skinned model: " + what);
  };
  const int node_count = static_cast<int>(model.nodes.size());
  const int joint_count = static_cast<int>(model.joint_nodes.size());
  if (joint_count == 0 || model.inverse_bind.size() != model.joint_nodes.size())
    return invalid("one inverse bind matrix per joint is needed");
  for (int n : model.joint_nodes)
    if (n < 0 || n >= node_count) return invalid("a joint node out of range");
  for (const GltfNode& n : model.nodes)
    if (n.parent >= node_count) return invalid("a parent out of range");
  if (model.mesh_node >= node_count) return invalid("the mesh node is out of range");
  if (model.vertices.empty() || model.triangles.empty()) return invalid("no vertices or triangles");
  for (const SkinVertex& v : model.vertices)
    if ((v.joints.array() < 0).any() || (v.joints.array() >= joint_count).any())
      return invalid("a vertex joint index out of range");
  for (const Eigen::Vector3i& t : model.triangles)
    if ((t.array() < 0).any() || (t.array() >= static_cast<int>(model.vertices.size())).any())
      return invalid("a triangle index out of range");

  auto data = std::make_shared<Data>();
  Data& d = *data;

  // Our joints from the skin's joint names.
  Expected<JointSetDefinition> def = GltfJointsByName(model.JointNames());
  if (!def.ok()) return Unsupported(model, def.error().message);
  std::string missing;
  for (int j = 0; j < kJointCount; ++j) {
    const Joint joint = static_cast<Joint>(j);
    d.joint_node[j] = -1;
    d.joint_offset[j] = Vector3d::Zero();
    const auto& recipes = def->recipes[j];
    if (!recipes.empty() && recipes[0].source.size() == 1) {
      d.joint_node[j] = model.joint_nodes[recipes[0].source[0]];
    } else if (joint != Joint::kTorso) {
      missing += (missing.empty() ? "" : ", ") + std::string(JointName(joint));
    }
  }
  if (!missing.empty())
    return Unsupported(model, "the skin's joint names give no joint for " + missing +
                                  " (names are matched as joint_maps.h describes)");
  const auto node = [&](Joint j) { return d.joint_node[Index(j)]; };
  const auto chain = [&](Joint a, Joint b) -> Status {
    if (!IsDescendant(model, node(b), node(a)))
      return Unsupported(model, "the skin's " + std::string(JointName(b)) + " joint '" +
                                    model.nodes[node(b)].name + "' is not below its " +
                                    std::string(JointName(a)) + " joint '" +
                                    model.nodes[node(a)].name + "'");
    return {};
  };
  std::vector<std::pair<Joint, Joint>> chains(kLimbBones.begin(), kLimbBones.end());
  chains.insert(chains.end(), {{Joint::kWaist, Joint::kNeck},
                               {Joint::kWaist, Joint::kLeftHip},
                               {Joint::kWaist, Joint::kRightHip},
                               {Joint::kWaist, Joint::kLeftShoulder},
                               {Joint::kWaist, Joint::kRightShoulder}});
  const bool torso_mapped = node(Joint::kTorso) >= 0;
  if (torso_mapped)
    chains.insert(chains.end(), {{Joint::kWaist, Joint::kTorso},
                                 {Joint::kTorso, Joint::kNeck},
                                 {Joint::kTorso, Joint::kLeftShoulder},
                                 {Joint::kTorso, Joint::kRightShoulder}});
  for (const auto& [a, b] : chains) {
    Status s = chain(a, b);
    if (!s.ok()) return s.error();
  }
  if (!torso_mapped) {
    const int pivot = ChildTowards(model, node(Joint::kWaist), node(Joint::kNeck));
    if (pivot != node(Joint::kNeck) && IsDescendant(model, node(Joint::kLeftShoulder), pivot) &&
        IsDescendant(model, node(Joint::kRightShoulder), pivot) &&
        !IsDescendant(model, node(Joint::kLeftHip), pivot) &&
        !IsDescendant(model, node(Joint::kRightHip), pivot))
      d.spine_pivot = pivot;
  }

  // The bind pose in the scene frame.
  d.bind_local = BindTransforms(model);
  const std::vector<Eigen::Affine3d> scene = SceneFromNode(model, d.bind_local);
  std::vector<Vector3d>& bind_vertices = d.bind_vertices;
  bind_vertices.resize(model.vertices.size());
  {
    std::vector<Eigen::Affine3d> m(joint_count);
    for (int j = 0; j < joint_count; ++j)
      m[j] = scene[model.joint_nodes[j]] * model.inverse_bind[j];
    for (size_t i = 0; i < model.vertices.size(); ++i) {
      const SkinVertex& v = model.vertices[i];
      Vector3d p = Vector3d::Zero();
      for (int k = 0; k < 4; ++k)
        if (v.weights[k] > 0) p += v.weights[k] * (m[v.joints[k]] * v.position);
      bind_vertices[i] = p;
    }
  }

  // Facing: scene (z, x, y) -> body (x, y, z), turned so that the left hip is on body +y.
  Matrix3d body_from_scene_r;
  body_from_scene_r << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  const Vector3d lateral = body_from_scene_r * (scene[node(Joint::kLeftHip)].translation() -
                                                scene[node(Joint::kRightHip)].translation());
  if (lateral.head<2>().norm() < 1e-9)
    return Unsupported(model,
                       "the bind pose's hips coincide in plan view; cannot tell left from right");
  const double phi = std::atan2(lateral.y(), lateral.x());
  const double quarter = std::numbers::pi / 2;
  const double psi = quarter * std::round((quarter - phi) / quarter);
  body_from_scene_r =
      Eigen::AngleAxisd(psi, Vector3d::UnitZ()).toRotationMatrix() * body_from_scene_r;

  double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
  for (const Vector3d& p : bind_vertices) {
    const double z = (body_from_scene_r * p).z();
    zmin = std::min(zmin, z);
    zmax = std::max(zmax, z);
  }
  const double model_height = zmax - zmin;
  if (!(model_height > 1e-6) || !std::isfinite(model_height))
    return MakeError("corrupt", model.path + ": the skinned mesh has no height in its bind pose");
  d.scale = options.height_m > 0 ? options.height_m / model_height : 1.0;
  d.height_m = d.scale * model_height;
  const Vector3d waist_b = body_from_scene_r * scene[node(Joint::kWaist)].translation();
  d.body_from_scene.linear() = d.scale * body_from_scene_r;
  d.body_from_scene.translation() = -d.scale * Vector3d(waist_b.x(), waist_b.y(), zmin);

  // Parts of the skin's joints.
  std::vector<int> our_joint_of_node(node_count, -1);
  for (int j = kJointCount - 1; j >= 0; --j)
    if (d.joint_node[j] >= 0) our_joint_of_node[d.joint_node[j]] = j;
  const Vector3d waist = scene[node(Joint::kWaist)].translation();
  const Vector3d spine = scene[node(Joint::kNeck)].translation() - waist;
  const double torso_t =
      torso_mapped
          ? (scene[node(Joint::kTorso)].translation() - waist).dot(spine) / spine.squaredNorm()
          : 0.5;
  std::vector<int> part_of_node(node_count, -1);
  const std::function<int(int)> node_part = [&](int n) -> int {
    if (part_of_node[n] >= 0) return part_of_node[n];
    int part;
    if (our_joint_of_node[n] >= 0) {
      part = Index(PartOfJoint(static_cast<Joint>(our_joint_of_node[n])));
    } else if (IsDescendant(model, n, node(Joint::kWaist)) &&
               IsDescendant(model, node(Joint::kNeck), n)) {
      const double t = (scene[n].translation() - waist).dot(spine) / spine.squaredNorm();
      part = Index(t > torso_t ? BodyPart::kUpperTorso : BodyPart::kLowerTorso);
    } else if (model.nodes[n].parent >= 0) {
      part = node_part(model.nodes[n].parent);
    } else {
      part = Index(BodyPart::kLowerTorso);
    }
    return part_of_node[n] = part;
  };
  for (int j = 0; j < joint_count; ++j)
    d.joint_part.push_back(static_cast<BodyPart>(node_part(model.joint_nodes[j])));
  // Torso vertices split at the torso joint's height along the spine, not by joint.
  const auto on_spine = [&](int n) {
    return n == node(Joint::kWaist) || (IsDescendant(model, n, node(Joint::kWaist)) &&
                                        IsDescendant(model, node(Joint::kNeck), n));
  };
  for (int j = 0; j < joint_count; ++j) d.joint_on_spine.push_back(on_spine(model.joint_nodes[j]));
  d.split_waist = waist;
  d.split_spine = spine;
  d.split_torso_t = torso_t;
  std::vector<int> dominant(model.vertices.size());
  for (size_t i = 0; i < model.vertices.size(); ++i) {
    int k;
    model.vertices[i].weights.maxCoeff(&k);
    dominant[i] = model.vertices[i].joints[k];
    d.vertex_part.push_back(d.PartAt(dominant[i], bind_vertices[i]));
  }

  // Head and hands: the centroid of their vertices, in the mapped node's frame.
  for (Joint j : {Joint::kHead, Joint::kLeftHand, Joint::kRightHand}) {
    const int n = node(j);
    Vector3d sum = Vector3d::Zero();
    int count = 0;
    for (size_t i = 0; i < model.vertices.size(); ++i) {
      const int dn = model.joint_nodes[dominant[i]];
      if (dn == n || IsDescendant(model, dn, n)) {
        sum += bind_vertices[i];
        ++count;
      }
    }
    if (count > 0) d.joint_offset[Index(j)] = scene[n].inverse() * (sum / count);
  }

  d.model = std::move(model);
  return SkinnedBody(std::move(data));
}

const GltfSkinModel& SkinnedBody::model() const { return data_->model; }
double SkinnedBody::height_m() const { return data_->height_m; }
double SkinnedBody::metres_per_unit() const { return data_->scale; }
const Eigen::Affine3d& SkinnedBody::body_from_scene() const { return data_->body_from_scene; }
BodyPart SkinnedBody::JointPart(int joint) const {
  REENACT_CHECK(joint >= 0 && joint < static_cast<int>(data_->joint_part.size()),
                "skin joint out of range");
  return data_->joint_part[joint];
}
const std::vector<BodyPart>& SkinnedBody::vertex_parts() const { return data_->vertex_part; }
int SkinnedBody::JointNode(Joint j) const { return data_->joint_node[Index(j)]; }
Eigen::Vector3d SkinnedBody::JointOffset(Joint j) const { return data_->joint_offset[Index(j)]; }

SkinPose SkinnedBody::BindPose(const Eigen::Isometry3d& world_from_body) const {
  return SkinPose{data_->bind_local, world_from_body};
}

SkinPose SkinnedBody::AnimationPose(int animation, double t_s,
                                    const Eigen::Isometry3d& world_from_body) const {
  SkinPose pose{SampleAnimation(data_->model, animation, t_s), world_from_body};
  PlaceOnFloor(&pose);
  return pose;
}

void SkinnedBody::PlaceOnFloor(SkinPose* pose) const {
  const PosedSkin posed = Skin(*pose);
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vector3d& p : posed.positions) lowest = std::min(lowest, p.z());
  pose->world_from_body.translation().z() -= lowest;
}

PosedSkin SkinnedBody::SkinJointsOnly(const SkinPose& pose) const {
  const Data& d = *data_;
  REENACT_CHECK(pose.local.size() == d.model.nodes.size(),
                "a skin pose needs one transform per node");
  PosedSkin out;
  const Eigen::Affine3d world_from_scene = pose.world_from_body * d.body_from_scene;
  out.world_from_node = SceneFromNode(d.model, pose.local);
  for (Eigen::Affine3d& t : out.world_from_node) t = world_from_scene * t;
  for (int j = 0; j < kJointCount; ++j) {
    const int n = d.joint_node[j];
    if (n >= 0) out.skeleton.Set(static_cast<Joint>(j), out.world_from_node[n] * d.joint_offset[j]);
  }
  if (d.joint_node[Index(Joint::kTorso)] < 0)
    out.skeleton.Set(Joint::kTorso,
                     0.5 * (out.skeleton[Joint::kNeck] + out.skeleton[Joint::kWaist]));
  return out;
}

PosedSkin SkinnedBody::Skin(const SkinPose& pose) const {
  const GltfSkinModel& m = data_->model;
  PosedSkin out = SkinJointsOnly(pose);
  using Matrix34 = Eigen::Matrix<double, 3, 4>;
  std::vector<Matrix34> joint(m.joint_nodes.size());
  for (size_t j = 0; j < joint.size(); ++j)
    joint[j] = (out.world_from_node[m.joint_nodes[j]] * m.inverse_bind[j]).matrix().topRows<3>();
  out.positions.resize(m.vertices.size());
  out.normals.resize(m.vertices.size());
  for (size_t i = 0; i < m.vertices.size(); ++i) {
    const SkinVertex& v = m.vertices[i];
    Matrix34 b = Matrix34::Zero();
    for (int k = 0; k < 4; ++k)
      if (v.weights[k] > 0) b += v.weights[k] * joint[v.joints[k]];
    const Matrix3d l = b.leftCols<3>();
    out.positions[i] = l * v.position + b.col(3);
    // Normals transform by the inverse transpose; a singular blend (opposed joints) falls back
    // to the dominant joint's.
    Matrix3d n_from = l;
    if (!(std::abs(l.determinant()) > 1e-12)) {
      int k;
      v.weights.maxCoeff(&k);
      n_from = joint[v.joints[k]].leftCols<3>();
    }
    const Vector3d n = n_from.inverse().transpose() * v.normal;
    out.normals[i] = n.norm() > 0 ? Vector3d(n.normalized()) : Vector3d::UnitZ();
  }
  return out;
}

Expected<SkinPose> SkinnedBody::RetargetPose(const Skeleton& target) const {
  const Data& d = *data_;
  for (Joint j : {Joint::kWaist, Joint::kLeftHip, Joint::kRightHip})
    if (!target.Has(j) || !target[j].allFinite())
      return MakeError("invalid_argument",
                       "cannot retarget onto a skeleton without its " + std::string(JointName(j)));
  const auto has = [&](Joint j) { return target.Has(j) && target[j].allFinite(); };
  const auto node = [&](Joint j) { return d.joint_node[Index(j)]; };

  Vector3d hips = target[Joint::kLeftHip] - target[Joint::kRightHip];
  const double yaw = hips.head<2>().norm() > 1e-9 ? std::atan2(hips.y(), hips.x()) : 0.0;
  SkinPose pose{d.bind_local, WorldFromBody(target[Joint::kWaist].head<2>(), yaw)};

  PosedSkin now = SkinJointsOnly(pose);
  const auto update = [&] { now = SkinJointsOnly(pose); };
  // Turns node n by the world rotation r about its origin.
  const auto rotate = [&](int n, const Matrix3d& r) {
    const int parent = d.model.nodes[n].parent;
    const Matrix3d p = parent >= 0 ? now.world_from_node[parent].linear()
                                   : (pose.world_from_body * d.body_from_scene).linear();
    const Matrix3d q = NearestRotation(p.inverse() * r * p);
    NodeTransform& t = pose.local[n];
    t.rotation = (Eigen::Quaterniond(q) * t.rotation).normalized();
    update();
  };
  const auto skin = [&](Joint j) { return now.skeleton[j]; };

  // 1. Pelvis.
  {
    const Vector3d lower_s = skin(Joint::kTorso) - skin(Joint::kWaist);
    const Vector3d lower_t =
        has(Joint::kTorso)  ? Vector3d(target[Joint::kTorso] - target[Joint::kWaist])
        : has(Joint::kNeck) ? Vector3d(target[Joint::kNeck] - target[Joint::kWaist])
                            : Vector3d(Vector3d::UnitZ());
    rotate(
        node(Joint::kWaist),
        TwoVectorRotation(lower_s, skin(Joint::kLeftHip) - skin(Joint::kRightHip), lower_t, hips));
  }
  // 2. Chest.
  const bool shoulders = has(Joint::kLeftShoulder) && has(Joint::kRightShoulder);
  const Vector3d shoulder_t =
      shoulders ? Vector3d(target[Joint::kLeftShoulder] - target[Joint::kRightShoulder])
                : Vector3d(Vector3d::Zero());
  if (node(Joint::kTorso) >= 0) {
    if (has(Joint::kTorso) && has(Joint::kNeck))
      rotate(node(Joint::kTorso),
             TwoVectorRotation(skin(Joint::kNeck) - skin(Joint::kTorso),
                               skin(Joint::kLeftShoulder) - skin(Joint::kRightShoulder),
                               target[Joint::kNeck] - target[Joint::kTorso], shoulder_t));
  } else if (d.spine_pivot >= 0 && has(Joint::kNeck)) {
    const Vector3d pivot = now.world_from_node[d.spine_pivot].translation();
    const Matrix3d aim = AimAbout(pivot, skin(Joint::kWaist), skin(Joint::kNeck),
                                  target[Joint::kNeck] - target[Joint::kWaist]);
    const Vector3d axis = aim * (skin(Joint::kNeck) - pivot);
    const Matrix3d twist = TwoVectorRotation(
        axis, aim * (skin(Joint::kLeftShoulder) - skin(Joint::kRightShoulder)), axis, shoulder_t);
    rotate(d.spine_pivot, twist * aim);
  }
  // 3. Limbs and head.
  for (const auto& [a, b] : kLimbBones) {
    if (!has(a) || !has(b)) continue;
    const Vector3d dir = target[b] - target[a];
    if (dir.norm() < 1e-9) continue;
    const std::optional<Matrix3d> r = RotationBetween(skin(b) - skin(a), dir);
    if (r) rotate(node(a), *r);
  }
  // 4. Placement: waist above the target's, lowest vertex on the floor.
  pose.world_from_body.translation().head<2>() +=
      target[Joint::kWaist].head<2>() - skin(Joint::kWaist).head<2>();
  PlaceOnFloor(&pose);
  return pose;
}

void SkinnedBody::Draw(const PosedSkin& posed, const Eigen::Isometry3d& camera_from_world,
                       Rasterizer* r, SyntheticView* view, double ambient) const {
  REENACT_CHECK(r->options().attribute_count >= 8, "drawing a skin needs 8 raster attributes");
  const Data& d = *data_;
  REENACT_CHECK(posed.positions.size() == d.model.vertices.size(), "posed skin of another body");
  auto shader = [&](const RasterFragment& f) {
    const Eigen::Vector2d uv(f.attributes[0], f.attributes[1]);
    const Vector3d normal =
        Vector3d(f.attributes[2], f.attributes[3], f.attributes[4]).normalized();
    const Vector3d c = SampleBaseColor(d.model, uv) * (LambertShade(normal, ambient) * 255.0);
    for (int k = 0; k < 3; ++k)
      view->color.at(f.x, f.y, k) = static_cast<uint8_t>(std::clamp(c[k] + 0.5, 0.0, 255.0));
    view->mask.at(f.x, f.y) = 255;
    const Vector3d bind(f.attributes[5], f.attributes[6], f.attributes[7]);
    view->part_labels.at(f.x, f.y) =
        static_cast<uint8_t>(PartLabel(d.PartOfSurfacePoint(f.primitive_id, bind)));
    return true;
  };
  std::vector<RasterVertex> vertices(posed.positions.size());
  for (size_t i = 0; i < vertices.size(); ++i) {
    vertices[i].position = camera_from_world * posed.positions[i];
    const SkinVertex& v = d.model.vertices[i];
    vertices[i].attributes[0] = static_cast<float>(v.uv.x());
    vertices[i].attributes[1] = static_cast<float>(v.uv.y());
    for (int k = 0; k < 3; ++k) {
      vertices[i].attributes[2 + k] = static_cast<float>(posed.normals[i][k]);
      vertices[i].attributes[5 + k] = static_cast<float>(d.bind_vertices[i][k]);
    }
  }
  r->DrawMesh(vertices, d.model.triangles, {}, shader);
}

}  // namespace reenact::capture
