#include "tests/eval/reference_agreement.h"

#include <algorithm>
#include <cmath>

#include "common/error/check.h"
#include "common/estimate/median.h"
#include "tests/eval/joint_error_table.h"

namespace reenact::eval {
namespace {

const Eigen::Vector3d* At(const JointPoints& pose, size_t j) {
  return j < pose.size() && pose[j] ? &*pose[j] : nullptr;
}

template <typename T>
std::optional<double> MeanOf(const std::vector<T>& values) {
  if (values.empty()) return std::nullopt;
  double sum = 0;
  for (const T& v : values) sum += v;
  return sum / values.size();
}

}  // namespace

void AgreementOptions::Check() const {
  REENACT_CHECK(min_travel_m > 0 && pck_m > 0, "min_travel_m and pck_m must be > 0");
  REENACT_CHECK(warmup_frames >= 0, "warmup_frames must be >= 0");
}

JointPoints PointsOf(const Skeleton& s) {
  JointPoints out(kJointCount);
  for (int j = 0; j < kJointCount; ++j)
    if (s.confidence[j] > 0 && s.position[j].allFinite()) out[j] = s.position[j];
  return out;
}

std::vector<bool> MovingJoints(const std::vector<std::optional<JointPoints>>& reference,
                               double min_travel_m) {
  size_t joints = 0;
  for (const auto& pose : reference)
    if (pose) joints = std::max(joints, pose->size());
  std::vector<bool> moving(joints, false);
  for (size_t j = 0; j < joints; ++j) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int n = 0;
    for (const auto& pose : reference)
      if (pose)
        if (const Eigen::Vector3d* p = At(*pose, j)) sum += *p, ++n;
    if (n == 0) continue;
    const Eigen::Vector3d mean = sum / n;
    for (const auto& pose : reference)
      if (pose)
        if (const Eigen::Vector3d* p = At(*pose, j); p && (*p - mean).norm() > min_travel_m)
          moving[j] = true;
  }
  return moving;
}

std::vector<std::optional<JointPoints>> MeanPoseAtCentre(
    const std::vector<std::optional<JointPoints>>& reference, int centre) {
  REENACT_CHECK(centre >= 0, "centre must be a joint index");
  size_t joints = 0;
  for (const auto& pose : reference)
    if (pose) joints = std::max(joints, pose->size());
  std::vector<Eigen::Vector3d> sum(joints, Eigen::Vector3d::Zero());
  std::vector<int> n(joints, 0);
  for (const auto& pose : reference) {
    if (!pose) continue;
    const Eigen::Vector3d* c = At(*pose, centre);
    if (!c) continue;
    for (size_t j = 0; j < joints; ++j)
      if (const Eigen::Vector3d* p = At(*pose, j)) sum[j] += *p - *c, ++n[j];
  }
  std::vector<std::optional<JointPoints>> out(reference.size());
  for (size_t f = 0; f < reference.size(); ++f) {
    if (!reference[f]) continue;
    const Eigen::Vector3d* c = At(*reference[f], centre);
    if (!c) continue;
    JointPoints& pose = out[f].emplace(joints);
    for (size_t j = 0; j < joints; ++j)
      if (n[j] > 0) pose[j] = *c + sum[j] / n[j];
  }
  return out;
}

std::optional<double> FrameAgreement::MeanM() const {
  return compared > 0 ? std::optional(sum_m / compared) : std::nullopt;
}

std::optional<double> FrameAgreement::MovingMeanM() const {
  return moving_compared > 0 ? std::optional(moving_sum_m / moving_compared) : std::nullopt;
}

FrameAgreement CompareFrame(const JointPoints& estimate, const JointPoints& reference,
                            const std::vector<bool>& moving, double pck_m) {
  FrameAgreement a;
  for (size_t j = 0; j < reference.size(); ++j) {
    const Eigen::Vector3d* r = At(reference, j);
    if (!r) continue;
    ++a.reference_joints;
    const Eigen::Vector3d* e = At(estimate, j);
    if (!e) continue;
    const double d = (*e - *r).norm();
    ++a.compared;
    a.sum_m += d;
    if (d <= pck_m) ++a.within;
    if (j < moving.size() && moving[j]) ++a.moving_compared, a.moving_sum_m += d;
  }
  return a;
}

SequenceAgreement CompareSequence(const std::vector<std::optional<JointPoints>>& estimate,
                                  const std::vector<std::optional<JointPoints>>& reference,
                                  const std::vector<bool>& moving,
                                  const AgreementOptions& options) {
  options.Check();
  SequenceAgreement s;
  for (bool m : moving) s.moving_joints += m;
  const size_t frames = std::max(estimate.size(), reference.size());
  s.frame_error_cm.resize(frames);
  std::vector<double> errors, moving_errors;
  for (size_t f = 0; f < frames; ++f) {
    const JointPoints* r = f < reference.size() && reference[f] ? &*reference[f] : nullptr;
    const JointPoints* e = f < estimate.size() && estimate[f] ? &*estimate[f] : nullptr;
    if (!r) continue;
    const bool warm = static_cast<int>(f) >= options.warmup_frames;
    ++s.frames;
    s.warm_frames += warm;
    if (!e) continue;
    ++s.tracked;
    s.warm_tracked += warm;
    if (!s.first_estimate) s.first_estimate = static_cast<int>(f);
    const FrameAgreement a = CompareFrame(*e, *r, moving, options.pck_m);
    s.reference_joints += a.reference_joints;
    s.given_joints += a.compared;
    s.compared += a.compared;
    s.within += a.within;
    if (const auto m = a.MeanM()) {
      errors.push_back(100 * *m);
      s.frame_error_cm[f] = errors.back();
    }
    if (const auto m = a.MovingMeanM()) moving_errors.push_back(100 * *m);
  }
  s.mpjpe_cm = MeanOf(errors);
  s.moving_mpjpe_cm = MeanOf(moving_errors);
  if (s.compared > 0) s.pck = static_cast<double>(s.within) / s.compared;
  if (s.reference_joints > 0)
    s.joint_share = static_cast<double>(s.given_joints) / s.reference_joints;
  if (s.warm_frames > 0) s.tracked_share = static_cast<double>(s.warm_tracked) / s.warm_frames;
  return s;
}

GroupAgreement Aggregate(const std::vector<const SequenceAgreement*>& sequences) {
  GroupAgreement g;
  std::vector<double> first, mpjpe, moving, pck, share;
  const auto collect = [](const std::optional<double>& v, std::vector<double>* into) {
    if (v) into->push_back(*v);
  };
  for (const SequenceAgreement* s : sequences) {
    ++g.sequences;
    g.frames += s->frames;
    g.tracked += s->tracked;
    g.warm_frames += s->warm_frames;
    g.warm_tracked += s->warm_tracked;
    if (s->tracked == 0) ++g.untracked_sequences;
    if (s->first_estimate) first.push_back(*s->first_estimate);
    collect(s->mpjpe_cm, &mpjpe);
    collect(s->moving_mpjpe_cm, &moving);
    collect(s->pck, &pck);
    collect(s->joint_share, &share);
  }
  if (g.warm_frames > 0) g.tracked_share = static_cast<double>(g.warm_tracked) / g.warm_frames;
  if (!first.empty()) g.first_estimate_median = Median(first);
  g.mpjpe_cm = MeanOf(mpjpe);
  g.moving_mpjpe_cm = MeanOf(moving);
  g.pck = MeanOf(pck);
  g.joint_share = MeanOf(share);
  return g;
}

JointOffsets::JointOffsets() {
  in_body.fill(Eigen::Vector3d::Zero());
  in_sensor.fill(Eigen::Vector3d::Zero());
}

Skeleton JointOffsets::Apply(const Skeleton& estimate) const {
  Skeleton out = estimate;
  const std::optional<Eigen::Matrix3d> body = BodyFrame(estimate);
  for (int j = 0; j < kJointCount; ++j) {
    if (!(estimate.confidence[j] > 0)) continue;
    out.position[j] += body ? Eigen::Vector3d(*body * in_body[j]) : in_sensor[j];
  }
  return out;
}

JointOffsetFit::JointOffsetFit() {
  body_sum_.fill(Eigen::Vector3d::Zero());
  sensor_sum_.fill(Eigen::Vector3d::Zero());
}

void JointOffsetFit::Add(const Skeleton& estimate, const Skeleton& reference) {
  ++frames_;
  const std::optional<Eigen::Matrix3d> body = BodyFrame(estimate);
  for (int j = 0; j < kJointCount; ++j) {
    if (!(estimate.confidence[j] > 0) || !(reference.confidence[j] > 0)) continue;
    const Eigen::Vector3d d = reference.position[j] - estimate.position[j];
    if (!d.allFinite()) continue;
    sensor_sum_[j] += d;
    ++sensor_n_[j];
    if (body) body_sum_[j] += body->transpose() * d, ++body_n_[j];
  }
}

void JointOffsetFit::Merge(const JointOffsetFit& other) {
  frames_ += other.frames_;
  for (int j = 0; j < kJointCount; ++j) {
    body_sum_[j] += other.body_sum_[j];
    sensor_sum_[j] += other.sensor_sum_[j];
    body_n_[j] += other.body_n_[j];
    sensor_n_[j] += other.sensor_n_[j];
  }
}

JointOffsets JointOffsetFit::Offsets() const {
  JointOffsets o;
  for (int j = 0; j < kJointCount; ++j) {
    if (body_n_[j] > 0) o.in_body[j] = body_sum_[j] / body_n_[j];
    if (sensor_n_[j] > 0) o.in_sensor[j] = sensor_sum_[j] / sensor_n_[j];
  }
  return o;
}

}  // namespace reenact::eval
