#include "synthetic/bvh_motion.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/error/check.h"
#include "common/skeleton/joint_maps.h"

namespace reenact::capture {
namespace {

// Our joints in the file's axes, metres, one per source frame.
using Frames = std::vector<Skeleton>;

std::string Join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// `set` must map file units to file units (metres_per_unit 1); scale makes them metres.
Expected<Frames> MapFrames(const BvhClip& clip, const JointSetDefinition& set, double scale) {
  const std::vector<int> named = clip.NamedJoints();
  Frames out;
  out.reserve(clip.frame_count());
  std::vector<Eigen::Vector3d> positions(named.size());
  for (int f = 0; f < clip.frame_count(); ++f) {
    const std::vector<Eigen::Vector3d> all = BvhJointPositions(clip, f);
    for (size_t i = 0; i < named.size(); ++i) positions[i] = all[named[i]];
    Expected<Skeleton> s = MapSkeleton(set, positions);
    if (!s.ok()) return s.error();
    for (auto& p : s->position) p *= scale;
    out.push_back(*s);
  }
  return out;
}

std::string MissingJoints(const Skeleton& s) {
  std::string missing;
  for (int j = 0; j < kJointCount; ++j)
    if (!s.Has(static_cast<Joint>(j)))
      missing += (missing.empty() ? "" : ", ") + std::string(JointName(static_cast<Joint>(j)));
  return missing;
}

double GuessMetresPerUnit(const Skeleton& first_in_units) {
  // Y up in the file.
  const double height =
      first_in_units[Joint::kHead].y() -
      std::min(first_in_units[Joint::kLeftFoot].y(), first_in_units[Joint::kRightFoot].y());
  double best = 1, best_error = INFINITY;
  for (double unit : {1.0, 0.01, 0.001, 0.0254}) {
    const double error =
        std::abs(std::log(std::max(std::abs(height) * unit, 1e-12) / kTypicalStature));
    if (error < best_error) best = unit, best_error = error;
  }
  return best;
}

Skeleton Lerp(const Skeleton& a, const Skeleton& b, double t) {
  Skeleton s = a;
  for (int j = 0; j < kJointCount; ++j)
    s.position[j] = a.position[j] + t * (b.position[j] - a.position[j]);
  return s;
}

}  // namespace

void BvhMotionOptions::Check() const {
  REENACT_CHECK(std::isfinite(frame_rate_hz) && frame_rate_hz > 0, "frame_rate_hz must be > 0");
  REENACT_CHECK(metres_per_unit == 0 || (std::isfinite(metres_per_unit) && metres_per_unit > 0),
                "metres_per_unit must be 0 (from the rig) or > 0");
  REENACT_CHECK(std::isfinite(ankle_height_m) && ankle_height_m >= 0,
                "ankle_height_m must be >= 0");
}

Expected<BvhMotion> BvhToSkeletons(const BvhClip& clip, const BvhMotionOptions& options) {
  options.Check();
  REENACT_CHECK(clip.frame_count() >= 1 && clip.frame_time_s > 0, "a parsed BVH clip");
  BvhMotion motion;
  motion.frame_rate_hz = options.frame_rate_hz;

  // 1. Joints.
  const std::vector<std::string> names = clip.NamedJointNames();
  JointSetDefinition set;
  if (names == CmuBvhJoints().source_names) {
    set = CmuBvhJoints();
    motion.joint_set = "cmu_bvh";
  } else {
    Expected<JointSetDefinition> by_name = JointsByName(names, "by_name");
    if (!by_name.ok())
      return MakeError("unsupported", "the BVH rig's joint names match none of ours (" +
                                          by_name.error().message +
                                          "); its joints: " + Join(names));
    set = std::move(by_name).value();
    motion.joint_set = "by_name";
  }
  set.metres_per_unit = 1;
  {
    std::vector<Eigen::Vector3d> first(names.size());
    const std::vector<Eigen::Vector3d> all = BvhJointPositions(clip, 0);
    const std::vector<int> named = clip.NamedJoints();
    for (size_t i = 0; i < named.size(); ++i) first[i] = all[named[i]];
    Expected<Skeleton> s = MapSkeleton(set, first);
    if (!s.ok()) return s.error();
    if (!s->Complete())
      return MakeError("unsupported",
                       "the BVH rig lacks joints for our " + MissingJoints(*s) +
                           "; its joints: " + Join(names) +
                           " (rename them to common names such as Hips, Spine, Neck, Head, "
                           "LeftArm, LeftForeArm, LeftHand, LeftUpLeg, LeftLeg, LeftFoot)");
    // 2. Units.
    if (options.metres_per_unit > 0)
      motion.metres_per_unit = options.metres_per_unit;
    else if (motion.joint_set == "cmu_bvh")
      motion.metres_per_unit = CmuBvhJoints().metres_per_unit;
    else
      motion.metres_per_unit = GuessMetresPerUnit(*s);
  }
  Expected<Frames> source = MapFrames(clip, set, motion.metres_per_unit);
  if (!source.ok()) return source.error();

  // 3. Axes, 4. placement from the first frame.
  const Eigen::Matrix3d world_from_file =
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Skeleton first = source->front().Transformed(Eigen::Isometry3d(world_from_file));
  Eigen::Vector3d left = (first[Joint::kLeftHip] - first[Joint::kRightHip]) +
                         (first[Joint::kLeftShoulder] - first[Joint::kRightShoulder]);
  left.z() = 0;
  if (!(left.norm() > 1e-6))
    return MakeError("unsupported",
                     "cannot tell which way the subject faces in the first BVH frame (its "
                     "left-right direction is vertical or zero)");
  const Eigen::Vector3d forward = left.normalized().cross(Eigen::Vector3d::UnitZ());
  // Turn about z taking `forward` to -y.
  const double yaw = std::atan2(-1.0, 0.0) - std::atan2(forward.y(), forward.x());
  Eigen::Isometry3d world_from_bvh = Eigen::Isometry3d::Identity();
  world_from_bvh.linear() =
      Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * world_from_file;
  const Skeleton turned = source->front().Transformed(world_from_bvh);
  const double lowest = std::min(turned[Joint::kLeftFoot].z(), turned[Joint::kRightFoot].z());
  world_from_bvh.translation() = Eigen::Vector3d(
      -turned[Joint::kWaist].x(), -turned[Joint::kWaist].y(), options.ankle_height_m - lowest);
  motion.world_from_bvh = world_from_bvh;

  // 5. Resampling.
  const int last = clip.frame_count() - 1;
  // The tolerance keeps the last frame of files whose Frame Time is rounded (".0083333").
  const int count =
      static_cast<int>(std::floor(clip.duration_s() * options.frame_rate_hz + 1e-3)) + 1;
  motion.skeletons.reserve(count);
  for (int k = 0; k < count; ++k) {
    const double u = std::min(k / options.frame_rate_hz / clip.frame_time_s, double(last));
    const int i = std::min(static_cast<int>(std::floor(u)), last);
    const int j = std::min(i + 1, last);
    const Skeleton s = Lerp((*source)[i], (*source)[j], u - i);
    motion.skeletons.push_back(s.Transformed(world_from_bvh));
  }
  return motion;
}

Expected<BvhMotion> LoadBvhMotion(const std::filesystem::path& path,
                                  const BvhMotionOptions& options) {
  Expected<BvhClip> clip = ReadBvhFile(path);
  if (!clip.ok()) return clip.error();
  Expected<BvhMotion> motion = BvhToSkeletons(*clip, options);
  if (!motion.ok())
    return MakeError(motion.error().code, path.string() + ": " + motion.error().message);
  return motion;
}

}  // namespace reenact::capture
