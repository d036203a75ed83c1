#include "capture-client/segment/body_bound.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "capture-client/segment/skeleton_bones.h"

namespace reenact::capture {

BodyBound::BodyBound(const Skeleton& skeleton, const PinholeCamera& camera, double margin)
    : margin2_(margin * margin) {
  std::array<bool, kJointCount> linked{};
  for (const Bone& bone : SkeletonBones()) {
    if (!skeleton.Has(bone.a) || !skeleton.Has(bone.b)) continue;
    bones_.push_back({skeleton[bone.a], skeleton[bone.b]});
    linked[Index(bone.a)] = linked[Index(bone.b)] = true;
  }
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY);
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-INFINITY);
  for (int j = 0; j < kJointCount; ++j) {
    const auto joint = static_cast<Joint>(j);
    if (!skeleton.Has(joint)) continue;
    const Eigen::Vector3d& p = skeleton[joint];
    if (!linked[j]) bones_.push_back({p, p});
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    if (p.z() > kNearM) behind_camera_ = false;
  }
  for (const BoneSegment& s : bones_) {
    const Eigen::Vector3d ab = s.b - s.a;
    const double len2 = ab.squaredNorm();
    capsules_.push_back({s.a, ab, len2 > 1e-12 ? 1.0 / len2 : 0.0});
  }
  if (bones_.empty() || behind_camera_) return;  // rect stays empty
  lo.array() -= margin;
  hi.array() += margin;
  if (lo.z() <= kNearM) {
    rect_ = {0, 0, camera.width, camera.height};
    return;
  }
  double u0 = INFINITY, v0 = INFINITY, u1 = -INFINITY, v1 = -INFINITY;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(),
                                 (c & 4) ? hi.z() : lo.z());
    const Eigen::Vector2d uv = *camera.Project(corner);  // z > kNearM: always in front
    u0 = std::min(u0, uv.x()), u1 = std::max(u1, uv.x());
    v0 = std::min(v0, uv.y()), v1 = std::max(v1, uv.y());
  }
  // Lens distortion bends the box's edges between its corners: a margin for it.
  const double pad =
      camera.distortion.IsZero() ? 1.0 : 0.02 * std::max(camera.width, camera.height);
  auto clamp = [](double value, int limit) {
    return static_cast<int>(std::clamp(value, 0.0, static_cast<double>(limit)));
  };
  rect_ = {clamp(std::floor(u0 - pad), camera.width), clamp(std::floor(v0 - pad), camera.height),
           clamp(std::ceil(u1 + pad) + 1, camera.width),
           clamp(std::ceil(v1 + pad) + 1, camera.height)};
}

bool BodyBound::NearBone(const Eigen::Vector3d& p, double radius2) const {
  for (const Capsule& c : capsules_) {
    const Eigen::Vector3d ap = p - c.a;
    const double t = std::clamp(ap.dot(c.ab) * c.inv_len2, 0.0, 1.0);
    if ((ap - t * c.ab).squaredNorm() <= radius2) return true;
  }
  return false;
}

}  // namespace reenact::capture
