#include "common/skeleton/joint_maps.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "common/error/check.h"

namespace reenact {
namespace {

// One recipe by source names: (name, weight) pairs.
using NamedRecipe = std::vector<std::pair<std::string, double>>;
// For each of our joints, its recipes in order of preference.
using NamedTable = std::vector<std::pair<Joint, std::vector<NamedRecipe>>>;

std::optional<int> FindName(const std::vector<std::string>& names, std::string_view name) {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) return std::nullopt;
  return static_cast<int>(it - names.begin());
}

// Builds a definition whose recipes all name joints of source_names (built-in tables).
JointSetDefinition Build(std::string name, std::vector<std::string> source_names,
                         const NamedTable& table, double metres_per_unit = 1.0) {
  JointSetDefinition def;
  def.name = std::move(name);
  def.source_names = std::move(source_names);
  def.metres_per_unit = metres_per_unit;
  for (const auto& [joint, recipes] : table) {
    for (const NamedRecipe& named : recipes) {
      JointRecipe recipe;
      for (const auto& [source, weight] : named) {
        const std::optional<int> index = FindName(def.source_names, source);
        REENACT_CHECK(index.has_value(), "built-in joint table names an unknown joint " + source);
        recipe.source.push_back(*index);
        recipe.weight.push_back(weight);
      }
      def.recipes[Index(joint)].push_back(std::move(recipe));
    }
  }
  def.Check();
  return def;
}

NamedRecipe One(std::string name) { return {{std::move(name), 1.0}}; }
NamedRecipe Mean(std::string a, std::string b) {
  return {{std::move(a), 0.5}, {std::move(b), 0.5}};
}

NamedTable NiteTable() {
  return {
      {Joint::kHead, {One("HEAD")}},
      {Joint::kNeck, {One("NECK")}},
      {Joint::kTorso, {One("TORSO")}},
      {Joint::kWaist, {Mean("LEFT_HIP", "RIGHT_HIP")}},
      {Joint::kLeftShoulder, {One("LEFT_SHOULDER")}},
      {Joint::kLeftElbow, {One("LEFT_ELBOW")}},
      {Joint::kLeftHand, {One("LEFT_HAND")}},
      {Joint::kRightShoulder, {One("RIGHT_SHOULDER")}},
      {Joint::kRightElbow, {One("RIGHT_ELBOW")}},
      {Joint::kRightHand, {One("RIGHT_HAND")}},
      {Joint::kLeftHip, {One("LEFT_HIP")}},
      {Joint::kLeftKnee, {One("LEFT_KNEE")}},
      {Joint::kLeftFoot, {One("LEFT_FOOT")}},
      {Joint::kRightHip, {One("RIGHT_HIP")}},
      {Joint::kRightKnee, {One("RIGHT_KNEE")}},
      {Joint::kRightFoot, {One("RIGHT_FOOT")}},
  };
}

// Name tables for JointsByName: normalised names in order of preference.
struct NameRow {
  Joint joint;
  std::vector<std::vector<std::string>> alternatives;  // each: names averaged with equal weight
};

// Long as one flat table of names: split, the rows would only be harder to compare.
const std::vector<NameRow>& NameRows() {
  static const std::vector<NameRow> rows = {
      {Joint::kHead, {{"head"}, {"skeletonneckjoint2"}}},
      {Joint::kNeck, {{"neck"}, {"shouldercenter"}, {"skeletonneckjoint1"}, {"lowerneck"}}},
      {Joint::kTorso, {{"chest", "chest2"}, {"spine1"}, {"chest"}, {"torso"}, {"spine"}}},
      {Joint::kWaist, {{"hips"}, {"pelvis"}, {"hipcenter"}, {"skeletontorsojoint1"}}},
      {Joint::kLeftShoulder,
       {{"leftarm"},
        {"leftupperarm"},
        {"upperarml"},
        {"leftshoulder"},
        {"shoulderleft"},
        {"lshoulder"},
        {"skeletonarmjointl4"}}},
      {Joint::kLeftElbow,
       {{"leftforearm"},
        {"leftlowerarm"},
        {"forearml"},
        {"lowerarml"},
        {"leftelbow"},
        {"elbowleft"},
        {"lelbow"},
        {"skeletonarmjointl3"}}},
      {Joint::kLeftHand,
       {{"lefthand"},
        {"handl"},
        {"handleft"},
        {"leftwrist"},
        {"wristleft"},
        {"lhand"},
        {"lwrist"},
        {"skeletonarmjointl2"}}},
      {Joint::kRightShoulder,
       {{"rightarm"},
        {"rightupperarm"},
        {"upperarmr"},
        {"rightshoulder"},
        {"shoulderright"},
        {"rshoulder"},
        {"skeletonarmjointr"}}},
      {Joint::kRightElbow,
       {{"rightforearm"},
        {"rightlowerarm"},
        {"forearmr"},
        {"lowerarmr"},
        {"rightelbow"},
        {"elbowright"},
        {"relbow"},
        {"skeletonarmjointr2"}}},
      {Joint::kRightHand,
       {{"righthand"},
        {"handr"},
        {"handright"},
        {"rightwrist"},
        {"wristright"},
        {"rhand"},
        {"rwrist"},
        {"skeletonarmjointr3"}}},
      {Joint::kLeftHip,
       {{"leftupleg"},
        {"leftupperleg"},
        {"thighl"},
        {"leftthigh"},
        {"lefthip"},
        {"hipleft"},
        {"lhip"},
        {"legjointl1"}}},
      {Joint::kLeftKnee,
       {{"leftleg"},
        {"leftlowerleg"},
        {"shinl"},
        {"leftshin"},
        {"leftcalf"},
        {"leftknee"},
        {"kneeleft"},
        {"lknee"},
        {"legjointl2"}}},
      {Joint::kLeftFoot,
       {{"leftfoot"},
        {"footl"},
        {"leftankle"},
        {"ankleleft"},
        {"footleft"},
        {"lfoot"},
        {"lankle"},
        {"legjointl3"}}},
      {Joint::kRightHip,
       {{"rightupleg"},
        {"rightupperleg"},
        {"thighr"},
        {"rightthigh"},
        {"righthip"},
        {"hipright"},
        {"rhip"},
        {"legjointr1"}}},
      {Joint::kRightKnee,
       {{"rightleg"},
        {"rightlowerleg"},
        {"shinr"},
        {"rightshin"},
        {"rightcalf"},
        {"rightknee"},
        {"kneeright"},
        {"rknee"},
        {"legjointr2"}}},
      {Joint::kRightFoot,
       {{"rightfoot"},
        {"footr"},
        {"rightankle"},
        {"ankleright"},
        {"footright"},
        {"rfoot"},
        {"rankle"},
        {"legjointr3"}}},
  };
  return rows;
}

}  // namespace

void JointSetDefinition::Check() const {
  REENACT_CHECK(std::isfinite(metres_per_unit) && metres_per_unit > 0,
                "metres_per_unit must be finite and > 0");
  const int n = static_cast<int>(source_names.size());
  for (const auto& recipes : this->recipes) {
    for (const JointRecipe& r : recipes) {
      REENACT_CHECK(!r.source.empty() && r.source.size() == r.weight.size(),
                    "a joint recipe needs one weight per source joint, at least one");
      double sum = 0;
      for (size_t i = 0; i < r.source.size(); ++i) {
        REENACT_CHECK(r.source[i] >= 0 && r.source[i] < n, "recipe source index out of range");
        REENACT_CHECK(std::isfinite(r.weight[i]) && r.weight[i] > 0, "recipe weight must be > 0");
        sum += r.weight[i];
      }
      REENACT_CHECK(std::abs(sum - 1.0) < 1e-9, "recipe weights must sum to 1");
    }
  }
}

const JointSetDefinition& KinectV1Joints() {
  static const JointSetDefinition def = Build(
      "kinect_v1", {"HipCenter",  "Spine",     "ShoulderCenter", "Head",          "ShoulderLeft",
                    "ElbowLeft",  "WristLeft", "HandLeft",       "ShoulderRight", "ElbowRight",
                    "WristRight", "HandRight", "HipLeft",        "KneeLeft",      "AnkleLeft",
                    "FootLeft",   "HipRight",  "KneeRight",      "AnkleRight",    "FootRight"},
      {
          {Joint::kHead, {One("Head")}},
          {Joint::kNeck, {One("ShoulderCenter")}},
          {Joint::kTorso, {One("Spine")}},
          {Joint::kWaist, {One("HipCenter")}},
          {Joint::kLeftShoulder, {One("ShoulderLeft")}},
          {Joint::kLeftElbow, {One("ElbowLeft")}},
          {Joint::kLeftHand, {One("HandLeft"), One("WristLeft")}},
          {Joint::kRightShoulder, {One("ShoulderRight")}},
          {Joint::kRightElbow, {One("ElbowRight")}},
          {Joint::kRightHand, {One("HandRight"), One("WristRight")}},
          {Joint::kLeftHip, {One("HipLeft")}},
          {Joint::kLeftKnee, {One("KneeLeft")}},
          {Joint::kLeftFoot, {One("AnkleLeft"), One("FootLeft")}},
          {Joint::kRightHip, {One("HipRight")}},
          {Joint::kRightKnee, {One("KneeRight")}},
          {Joint::kRightFoot, {One("AnkleRight"), One("FootRight")}},
      });
  return def;
}

const JointSetDefinition& NiteJoints() {
  static const JointSetDefinition def =
      Build("nite",
            {"HEAD", "NECK", "TORSO", "LEFT_SHOULDER", "LEFT_ELBOW", "LEFT_HAND", "RIGHT_SHOULDER",
             "RIGHT_ELBOW", "RIGHT_HAND", "LEFT_HIP", "LEFT_KNEE", "LEFT_FOOT", "RIGHT_HIP",
             "RIGHT_KNEE", "RIGHT_FOOT"},
            NiteTable());
  return def;
}

const JointSetDefinition& Nite2Joints() {
  static const JointSetDefinition def =
      Build("nite2",
            {"HEAD", "NECK", "LEFT_SHOULDER", "RIGHT_SHOULDER", "LEFT_ELBOW", "RIGHT_ELBOW",
             "LEFT_HAND", "RIGHT_HAND", "TORSO", "LEFT_HIP", "RIGHT_HIP", "LEFT_KNEE", "RIGHT_KNEE",
             "LEFT_FOOT", "RIGHT_FOOT"},
            NiteTable());
  return def;
}

const JointSetDefinition& CmuBvhJoints() {
  static const JointSetDefinition def =
      Build("cmu_bvh",
            {"Hips",         "LHipJoint",     "LeftHip",    "LeftKnee",   "LeftAnkle", "LeftToe",
             "RHipJoint",    "RightHip",      "RightKnee",  "RightAnkle", "RightToe",  "lowerback",
             "Chest",        "Chest2",        "lowerneck",  "Neck",       "Head",      "LeftCollar",
             "LeftShoulder", "LeftElbow",     "LeftWrist",  "lhand",      "LFingers",  "LThumb",
             "RightCollar",  "RightShoulder", "RightElbow", "RightWrist", "rhand",     "RFingers",
             "RThumb"},
            {
                {Joint::kHead, {One("Head")}},
                {Joint::kNeck, {One("Neck")}},
                {Joint::kTorso, {Mean("Chest", "Chest2")}},
                {Joint::kWaist, {One("Hips")}},
                {Joint::kLeftShoulder, {One("LeftShoulder")}},
                {Joint::kLeftElbow, {One("LeftElbow")}},
                {Joint::kLeftHand, {One("LeftWrist"), One("lhand")}},
                {Joint::kRightShoulder, {One("RightShoulder")}},
                {Joint::kRightElbow, {One("RightElbow")}},
                {Joint::kRightHand, {One("RightWrist"), One("rhand")}},
                {Joint::kLeftHip, {One("LeftHip")}},
                {Joint::kLeftKnee, {One("LeftKnee")}},
                {Joint::kLeftFoot, {One("LeftAnkle")}},
                {Joint::kRightHip, {One("RightHip")}},
                {Joint::kRightKnee, {One("RightKnee")}},
                {Joint::kRightFoot, {One("RightAnkle")}},
            },
            0.0254 / 0.45);
  return def;
}

std::string NormalizeJointName(std::string_view name) {
  const size_t cut = name.find_last_of(":|");
  if (cut != std::string_view::npos) name.remove_prefix(cut + 1);
  std::string out;
  for (char c : name)
    if (std::isalnum(static_cast<unsigned char>(c)))
      out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  return out;
}

Expected<JointSetDefinition> JointsByName(std::vector<std::string> names, std::string set_name) {
  if (names.empty())
    return MakeError("invalid_argument", "joint set '" + set_name + "' has no joint names");
  std::unordered_map<std::string, int> index;
  for (size_t i = 0; i < names.size(); ++i) {
    const std::string key = NormalizeJointName(names[i]);
    if (key.empty()) continue;
    if (!index.emplace(key, static_cast<int>(i)).second)
      return MakeError("invalid_argument", "joint set '" + set_name + "': joint names '" +
                                               names[index[key]] + "' and '" + names[i] +
                                               "' are the same after normalisation");
  }

  JointSetDefinition def;
  def.name = std::move(set_name);
  def.source_names = std::move(names);
  for (const NameRow& row : NameRows()) {
    for (const auto& alternative : row.alternatives) {
      JointRecipe recipe;
      for (const std::string& name : alternative) {
        const auto it = index.find(name);
        if (it == index.end()) break;
        recipe.source.push_back(it->second);
        recipe.weight.push_back(1.0 / alternative.size());
      }
      if (recipe.source.size() == alternative.size())
        def.recipes[Index(row.joint)].push_back(std::move(recipe));
    }
  }
  // Fallbacks for joints that many rigs lack: midpoints of joints that were matched.
  const auto midpoint_fallback = [&def](Joint target, Joint a, Joint b) {
    auto& ra = def.recipes[Index(a)];
    auto& rb = def.recipes[Index(b)];
    if (!def.recipes[Index(target)].empty() || ra.empty() || rb.empty() ||
        ra.front().source.size() != 1 || rb.front().source.size() != 1)
      return;
    def.recipes[Index(target)].push_back(
        JointRecipe{{ra.front().source[0], rb.front().source[0]}, {0.5, 0.5}});
  };
  midpoint_fallback(Joint::kWaist, Joint::kLeftHip, Joint::kRightHip);
  midpoint_fallback(Joint::kTorso, Joint::kNeck, Joint::kWaist);

  const bool any =
      std::any_of(def.recipes.begin(), def.recipes.end(), [](const auto& r) { return !r.empty(); });
  if (!any)
    return MakeError("invalid_argument", "joint set '" + def.name +
                                             "': no joint name matches a known body joint "
                                             "(expected names such as Hips, Neck, LeftArm)");
  def.Check();
  return def;
}

Expected<JointSetDefinition> GltfJointsByName(std::vector<std::string> names) {
  return JointsByName(std::move(names), "gltf_skin");
}

Expected<Skeleton> MapSkeleton(const JointSetDefinition& definition,
                               std::span<const Eigen::Vector3d> positions,
                               std::span<const double> confidences) {
  definition.Check();
  const size_t n = definition.source_names.size();
  if (positions.size() != n)
    return MakeError("invalid_argument", "joint set '" + definition.name + "' has " +
                                             std::to_string(n) + " joints but " +
                                             std::to_string(positions.size()) +
                                             " positions were given");
  if (!confidences.empty() && confidences.size() != n)
    return MakeError("invalid_argument", "joint set '" + definition.name + "' has " +
                                             std::to_string(n) + " joints but " +
                                             std::to_string(confidences.size()) +
                                             " confidences were given");
  for (size_t i = 0; i < confidences.size(); ++i)
    if (!(confidences[i] >= 0 && confidences[i] <= 1))
      return MakeError("invalid_argument", "joint set '" + definition.name + "': confidence of " +
                                               definition.source_names[i] + " must lie in [0, 1]");

  const auto confidence = [&](int i) {
    if (!positions[i].allFinite()) return 0.0;
    return confidences.empty() ? 1.0 : confidences[i];
  };
  Skeleton out;
  for (int j = 0; j < kJointCount; ++j) {
    for (const JointRecipe& recipe : definition.recipes[j]) {
      double conf = 1.0;
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (size_t k = 0; k < recipe.source.size(); ++k) {
        conf = std::min(conf, confidence(recipe.source[k]));
        if (conf > 0) p += recipe.weight[k] * positions[recipe.source[k]];
      }
      p *= definition.metres_per_unit;
      if (!(conf > 0) || !p.allFinite()) continue;
      out.Set(static_cast<Joint>(j), p, conf);
      break;
    }
  }
  return out;
}

}  // namespace reenact
