#include "capture-client/tracker/limb_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

using S = BodySegment;

struct LimbCapsule {
  bool lower;  // on the lower (hinge) segment
  Eigen::Vector3d a, b;
  double radius;
};

double AxisDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& p) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - a - t * ab).norm();
}

// The upper segment's directions: a cube's faces, edges and corners; the held hypotheses'
// index follows them.
constexpr int kCubeDirectionCount = 26;
static_assert(kHeldLimbDirection == kCubeDirectionCount);
// Two clamped hypotheses of one direction closer than this (radians; the hinge angle and each
// entry of the upper segment's rotation) are one.
constexpr double kSameAngle = 1e-9;

// One hypothesis and its cost.
struct ScoredHypothesis {
  double cost;
  LimbHypothesis h;
  int lost_taken;  // lost points (see ScoreLimbHypotheses) within outlier_m of the limb
};

// `pose` with the limb posed as `h` (as scored: every joint clamped to the limits).
ArticulatedPose WithLimb(const ArticulatedPose& pose, Limb limb, const LimbHypothesis& h,
                         const JointLimits& limits) {
  ArticulatedPose out = pose;
  out.local[static_cast<int>(LimbUpper(limb))] = h.upper_local;
  out.hinge_angle[static_cast<int>(LimbLower(limb))] = h.hinge_angle;
  ArticulatedBody::Clamp(&out, limits);
  return out;
}

// The search's cost (see the header) of posings of one limb at `pose`, the rest of the body
// held. Built once per limb and pose: each point's residual to the held body, and the points
// whose cost no posing of the limb can change (summed once).
class LimbPosingCost {
 public:
  LimbPosingCost(const ArticulatedBody& body, const BodyObservation& obs, const BodyFitOptions& fit,
                 const LimbSearchOptions& options, const ArticulatedPose& pose, Limb limb);

  // The cost with the limb posed as in `candidate`; taken(): how many lost points (MarkLost)
  // it brought within outlier_m of the limb.
  double CostOf(const ArticulatedPose& candidate);
  int taken() const { return taken_; }
  // Marks the points `pose` leaves beyond outlier_m of every capsule, the limb as last posed
  // by CostOf included; returns how many.
  int MarkLost();

 private:
  void PoseLimb(const ArticulatedPose& candidate);
  // Residual of a point to the limb as last posed, where it is below `below`; infinity where
  // it is not (a capsule whose bounding sphere lies farther than `below` from the point cannot
  // bring the residual under it, so its distance is not computed).
  double LimbResidual(const Eigen::Vector3d& p,
                      double below = std::numeric_limits<double>::infinity()) const;

  const BodyObservation& obs_;
  const BodyFitOptions& fit_;
  S upper_, lower_;
  double cap_cost_, w_sil_;
  Eigen::Isometry3d parent_;
  Eigen::Vector3d joint_, lower_offset_;
  double sign_;
  std::vector<LimbCapsule> local_;
  std::vector<double> rest_;  // each point's residual to the held body
  double fixed_cost_ = 0;
  std::vector<int> active_;  // the points whose cost the limb can change
  // The limb's posed capsules' axes and bounding spheres (midpoint, half length + radius).
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> axes_;
  std::vector<std::pair<Eigen::Vector3d, double>> spheres_;
  // is_lost_[j] for active_[j]: beyond outlier_m of the held body and of the limb at `pose`.
  std::vector<char> is_lost_;
  // below_[j]: the residual under which the limb changes active_[j]'s term: its cost (under
  // min(rest, cap_m)) or, for a lost point, whether it is taken (within outlier_m).
  std::vector<double> below_;
  int taken_ = 0;
};

LimbPosingCost::LimbPosingCost(const ArticulatedBody& body, const BodyObservation& obs,
                               const BodyFitOptions& fit, const LimbSearchOptions& options,
                               const ArticulatedPose& pose, Limb limb)
    : obs_(obs),
      fit_(fit),
      upper_(LimbUpper(limb)),
      lower_(LimbLower(limb)),
      cap_cost_(HuberCost(options.cap_m, fit.huber_m)),
      w_sil_(SilhouetteSampleWeight(obs, fit, static_cast<int>(body.capsules().size()))),
      lower_offset_(body.offset(lower_)),
      sign_(lower_ == S::kLeftForearm || lower_ == S::kRightForearm ? -1.0 : 1.0),
      rest_(obs.points.size(), std::numeric_limits<double>::infinity()) {
  const PosedBody3 posed = body.Pose(pose);
  parent_ = posed.sensor_from_segment[SegmentParent(upper_)];
  joint_ = posed.sensor_from_segment[static_cast<int>(upper_)].translation();
  double reach = 0;  // of the limb's capsules from the joint
  for (const BodyCapsule& c : body.capsules()) {
    if (c.segment == upper_ || c.segment == lower_) {
      const bool is_lower = c.segment == lower_;
      local_.push_back({is_lower, c.a, c.b, c.radius});
      // The lower segment turns about its joint: the joint's offset plus the point's.
      const double base = is_lower ? lower_offset_.norm() : 0.0;
      reach = std::max(reach, base + std::max(c.a.norm(), c.b.norm()) + c.radius);
      continue;
    }
    const Eigen::Isometry3d& t = posed.sensor_from_segment[static_cast<int>(c.segment)];
    const Eigen::Vector3d a = t * c.a, b = t * c.b;
    for (size_t i = 0; i < obs.points.size(); ++i)
      rest_[i] = std::min(rest_[i], AxisDistance(a, b, obs.points[i]) - c.radius);
  }
  // A point whose distance to any posing of the limb (at least |p - joint| - reach) cannot
  // fall below min(rest, cap_m) costs the same for every hypothesis.
  for (size_t i = 0; i < obs.points.size(); ++i) {
    if ((obs.points[i] - joint_).norm() - reach >= std::min(rest_[i], options.cap_m))
      fixed_cost_ += std::min(HuberCost(rest_[i], fit.huber_m), cap_cost_);
    else
      active_.push_back(static_cast<int>(i));
  }
  axes_.resize(local_.size());
  spheres_.resize(local_.size());
  is_lost_.assign(active_.size(), 0);
  below_.resize(active_.size());
  for (size_t j = 0; j < active_.size(); ++j)
    below_[j] = std::min(rest_[active_[j]], options.cap_m);
}

double LimbPosingCost::LimbResidual(const Eigen::Vector3d& p, double below) const {
  double e = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < axes_.size(); ++k) {
    const double r = spheres_[k].second + below;
    if ((p - spheres_[k].first).squaredNorm() > r * r) continue;
    e = std::min(e, AxisDistance(axes_[k].first, axes_[k].second, p) - local_[k].radius);
  }
  return e < below ? e : std::numeric_limits<double>::infinity();
}

void LimbPosingCost::PoseLimb(const ArticulatedPose& candidate) {
  // Upper rotation from the parent, lower by the hinge.
  Eigen::Isometry3d tu = Eigen::Isometry3d::Identity();
  tu.linear() = parent_.linear() * candidate.local[static_cast<int>(upper_)];
  tu.translation() = joint_;
  Eigen::Isometry3d tl = Eigen::Isometry3d::Identity();
  tl.linear() =
      tu.linear() * Eigen::AngleAxisd(sign_ * candidate.hinge_angle[static_cast<int>(lower_)],
                                      Eigen::Vector3d::UnitY())
                        .toRotationMatrix();
  tl.translation() = tu * lower_offset_;
  for (size_t k = 0; k < local_.size(); ++k) {
    const Eigen::Isometry3d& t = local_[k].lower ? tl : tu;
    axes_[k] = {t * local_[k].a, t * local_[k].b};
    spheres_[k] = {0.5 * (axes_[k].first + axes_[k].second),
                   0.5 * (axes_[k].second - axes_[k].first).norm() + local_[k].radius};
  }
}

double LimbPosingCost::CostOf(const ArticulatedPose& candidate) {
  PoseLimb(candidate);
  double cost = fixed_cost_;
  taken_ = 0;
  for (size_t j = 0; j < active_.size(); ++j) {
    const int i = active_[j];
    const double e_limb = LimbResidual(obs_.points[i], below_[j]);
    taken_ += is_lost_[j] && e_limb <= fit_.outlier_m;
    cost += std::min(HuberCost(std::min(rest_[i], e_limb), fit_.huber_m), cap_cost_);
  }
  const int m = fit_.samples_per_capsule;
  for (const auto& [a, b] : axes_)
    for (int i = 0; i < m; ++i) {
      const double t = m == 1 ? 0.5 : static_cast<double>(i) / (m - 1);
      double e = 0;
      Eigen::Vector3d grad;
      if (SilhouetteResidual(obs_, a + t * (b - a), &e, &grad)) cost += 0.5 * w_sil_ * e * e;
    }
  return cost;
}

int LimbPosingCost::MarkLost() {
  int n_lost = 0;
  for (size_t j = 0; j < active_.size(); ++j) {
    const int i = active_[j];
    if (rest_[i] > fit_.outlier_m && LimbResidual(obs_.points[i]) > fit_.outlier_m) {
      is_lost_[j] = 1, ++n_lost;
      below_[j] = std::max(below_[j], std::nextafter(fit_.outlier_m, 1.0));
    }
  }
  return n_lost;
}

// The search's cost of every hypothesis for `limb` at `pose`, and of `pose` itself
// (*current). *lost: the points `pose` leaves beyond outlier_m of every capsule that some
// posing of the limb can reach; no hypothesis is scored (empty) unless there are more than
// min_lost of them.
std::vector<ScoredHypothesis> ScoreLimbHypotheses(
    const ArticulatedBody& body, const BodyObservation& obs, const BodyFitOptions& fit,
    const JointLimits& limits, const LimbSearchOptions& options, const ArticulatedPose& pose,
    Limb limb, double* current, int* lost, double min_lost) {
  LimbPosingCost posing(body, obs, fit, options, pose, limb);
  *current = posing.CostOf(pose);
  const int n_lost = posing.MarkLost();
  *lost = n_lost;
  std::vector<ScoredHypothesis> scored;
  if (n_lost <= min_lost) return scored;
  const std::vector<LimbHypothesis> hypotheses = LimbHypotheses(pose, limb, limits, options);
  scored.reserve(hypotheses.size());
  ArticulatedPose candidate = pose;
  const int upper = static_cast<int>(LimbUpper(limb)), lower = static_cast<int>(LimbLower(limb));
  for (const LimbHypothesis& h : hypotheses) {
    candidate.local[upper] = h.upper_local;
    candidate.hinge_angle[lower] = h.hinge_angle;
    const double cost = posing.CostOf(candidate);
    scored.push_back({cost, h, posing.taken()});
  }
  return scored;
}

}  // namespace

void LimbSearchOptions::Check() const {
  REENACT_CHECK(cap_m > 0 && min_gain >= 0 && min_gain < 1, "cap_m > 0, 0 <= min_gain < 1");
  REENACT_CHECK(min_lost_share >= 0 && min_lost_share <= 1, "min_lost_share in [0, 1]");
  REENACT_CHECK(held_twists >= 0, "held_twists must be >= 0");
}

std::vector<LimbHypothesis> LimbHypotheses(const ArticulatedPose& pose, Limb limb,
                                           const JointLimits& limits,
                                           const LimbSearchOptions& options) {
  options.Check();
  const int upper = static_cast<int>(LimbUpper(limb)), lower = static_cast<int>(LimbLower(limb));
  std::vector<LimbHypothesis> out;
  out.reserve(kCubeDirectionCount * 9 + options.held_twists * 5);
  auto add = [&](const Eigen::Matrix3d& upper_local, double hinge_deg, int direction) {
    ArticulatedPose candidate = pose;
    candidate.local[upper] = upper_local;
    candidate.hinge_angle[lower] = hinge_deg * std::numbers::pi / 180;
    ArticulatedBody::Clamp(&candidate, limits);
    const LimbHypothesis h{direction, candidate.local[upper], candidate.hinge_angle[lower]};
    for (auto k = out.rbegin(); k != out.rend() && k->direction == direction; ++k)
      if (std::abs(k->hinge_angle - h.hinge_angle) <= kSameAngle &&
          (k->upper_local - h.upper_local).cwiseAbs().maxCoeff() <= kSameAngle)
        return;
    out.push_back(h);
  };
  int direction = 0;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k) {
        if (!i && !j && !k) continue;
        // The bone points along d (in the parent's frame); the segment's z axis points back
        // to the joint.
        const Eigen::Vector3d z = -Eigen::Vector3d(i, j, k).normalized();
        Eigen::Vector3d x0 = Eigen::Vector3d::UnitX() - z.x() * z;
        if (x0.norm() < 1e-6) x0 = Eigen::Vector3d::UnitZ() - z.z() * z;
        x0.normalize();
        for (double angle : {0.0, 60.0, 110.0})
          for (int twist = 0; twist < (angle == 0 ? 1 : 4); ++twist) {
            const Eigen::Vector3d x = Eigen::AngleAxisd(twist * std::numbers::pi / 2, z) * x0;
            Eigen::Matrix3d rotation;
            rotation.col(0) = x;
            rotation.col(1) = z.cross(x);
            rotation.col(2) = z;
            add(rotation, angle, direction);
          }
        ++direction;
      }
  // The upper segment held (its bone keeps its direction), the hinge's plane turned about it:
  // a forearm or shin swung where the local fit lost it while its upper segment is tracked.
  const Eigen::Matrix3d& held = pose.local[upper];
  for (int twist = 0; twist < options.held_twists; ++twist) {
    const Eigen::Matrix3d turned =
        held * Eigen::AngleAxisd(twist * 2 * std::numbers::pi / options.held_twists,
                                 Eigen::Vector3d::UnitZ())
                   .toRotationMatrix();
    for (double angle : {20.0, 45.0, 70.0, 95.0, 120.0}) add(turned, angle, kHeldLimbDirection);
  }
  return out;
}

int SearchLimbs(const ArticulatedBody& body, const BodyObservation& obs, const BodyFitOptions& fit,
                const JointLimits& limits, const LimbSearchOptions& options,
                ArticulatedPose* pose) {
  options.Check();
  if (obs.points.empty()) return 0;
  int changed = 0;
  std::array<bool, kLimbCount> moved{};
  for (int round = 0; round < kLimbCount; ++round) {
    int pick = -1;
    ScoredHypothesis pick_h{};
    double pick_gain = 0;
    for (int l = 0; l < kLimbCount; ++l) {
      if (moved[l]) continue;
      double current = 0;
      int lost = 0;
      const std::vector<ScoredHypothesis> scored =
          ScoreLimbHypotheses(body, obs, fit, limits, options, *pose, static_cast<Limb>(l),
                              &current, &lost, options.min_lost_share * obs.points.size());
      const ScoredHypothesis* best = nullptr;
      for (const ScoredHypothesis& h : scored)
        if (2 * h.lost_taken >= lost && (!best || h.cost < best->cost)) best = &h;
      if (!best || best->cost >= (1 - options.min_gain) * current) continue;
      const double gain = current - best->cost;
      if (pick < 0 || best->lost_taken > pick_h.lost_taken ||
          (best->lost_taken == pick_h.lost_taken && gain > pick_gain))
        pick = l, pick_h = *best, pick_gain = gain;
    }
    if (pick < 0) break;
    *pose = WithLimb(*pose, static_cast<Limb>(pick), pick_h.h, limits);
    moved[pick] = true;
    ++changed;
  }
  return changed;
}

}  // namespace reenact::capture
