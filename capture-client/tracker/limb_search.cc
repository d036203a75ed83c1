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

// The search's cost (see the header) of every hypothesis for `limb` at `pose`, and of `pose`
// itself (*current). *lost: the points `pose` leaves beyond outlier_m of every capsule that
// some posing of the limb can reach; no hypothesis is scored (empty) unless there are more
// than min_lost of them.
std::vector<ScoredHypothesis> ScoreLimbHypotheses(
    const ArticulatedBody& body, const BodyObservation& obs, const BodyFitOptions& fit,
    const JointLimits& limits, const LimbSearchOptions& options, const ArticulatedPose& pose,
    Limb limb, double* current, int* lost = nullptr, double min_lost = -1) {
  const S upper = LimbUpper(limb), lower = LimbLower(limb);
  const double delta = fit.huber_m;
  const double cap_cost = HuberCost(options.cap_m, delta);
  const double w_sil = SilhouetteSampleWeight(obs, fit, static_cast<int>(body.capsules().size()));
  const int m = fit.samples_per_capsule;
  const PosedBody3 posed = body.Pose(pose);
  const Eigen::Isometry3d& parent = posed.sensor_from_segment[SegmentParent(upper)];
  const Eigen::Vector3d joint = posed.sensor_from_segment[static_cast<int>(upper)].translation();
  const Eigen::Vector3d lower_offset = body.offset(lower);
  const double sign = lower == S::kLeftForearm || lower == S::kRightForearm ? -1.0 : 1.0;

  // Residual of every point to the held body; the limb's capsules and its reach from the joint.
  std::vector<LimbCapsule> local;
  std::vector<double> rest(obs.points.size(), std::numeric_limits<double>::infinity());
  double reach = 0;
  for (const BodyCapsule& c : body.capsules()) {
    if (c.segment == upper || c.segment == lower) {
      const bool is_lower = c.segment == lower;
      local.push_back({is_lower, c.a, c.b, c.radius});
      // The lower segment turns about its joint: the joint's offset plus the point's.
      const double base = is_lower ? lower_offset.norm() : 0.0;
      reach = std::max(reach, base + std::max(c.a.norm(), c.b.norm()) + c.radius);
      continue;
    }
    const Eigen::Isometry3d& t = posed.sensor_from_segment[static_cast<int>(c.segment)];
    const Eigen::Vector3d a = t * c.a, b = t * c.b;
    for (size_t i = 0; i < obs.points.size(); ++i)
      rest[i] = std::min(rest[i], AxisDistance(a, b, obs.points[i]) - c.radius);
  }
  // A point whose distance to any posing of the limb (at least |p - joint| - reach) cannot
  // fall below min(rest, cap_m) costs the same for every hypothesis.
  double fixed_cost = 0;
  std::vector<int> active;
  for (size_t i = 0; i < obs.points.size(); ++i) {
    if ((obs.points[i] - joint).norm() - reach >= std::min(rest[i], options.cap_m))
      fixed_cost += std::min(HuberCost(rest[i], delta), cap_cost);
    else
      active.push_back(static_cast<int>(i));
  }

  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> axes(local.size());
  // Each posed capsule's bounding sphere: its axis's midpoint, half its length plus its radius.
  std::vector<std::pair<Eigen::Vector3d, double>> spheres(local.size());
  // Residual of a point to the limb as last posed by cost_of, where it is below `below`;
  // infinity where it is not (a capsule whose bounding sphere lies farther than `below` from
  // the point cannot bring the residual under it, so its distance is not computed).
  auto limb_residual = [&](const Eigen::Vector3d& p,
                           double below = std::numeric_limits<double>::infinity()) {
    double e = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < axes.size(); ++k) {
      const double r = spheres[k].second + below;
      if ((p - spheres[k].first).squaredNorm() > r * r) continue;
      e = std::min(e, AxisDistance(axes[k].first, axes[k].second, p) - local[k].radius);
    }
    return e < below ? e : std::numeric_limits<double>::infinity();
  };
  // is_lost[j] for active[j]: beyond outlier_m of the held body and of the limb at `pose`;
  // taken: how many of them the last posing brought within outlier_m of the limb.
  std::vector<char> is_lost(active.size(), 0);
  // below[j]: the residual under which the limb changes active[j]'s term: its cost (under
  // min(rest, cap_m)) or, for a lost point, whether it is taken (within outlier_m).
  std::vector<double> below(active.size());
  for (size_t j = 0; j < active.size(); ++j) below[j] = std::min(rest[active[j]], options.cap_m);
  int taken = 0;
  auto cost_of = [&](const ArticulatedPose& candidate) {
    // Pose only this limb: upper rotation from the parent, lower by the hinge.
    Eigen::Isometry3d tu = Eigen::Isometry3d::Identity();
    tu.linear() = parent.linear() * candidate.local[static_cast<int>(upper)];
    tu.translation() = joint;
    Eigen::Isometry3d tl = Eigen::Isometry3d::Identity();
    tl.linear() =
        tu.linear() * Eigen::AngleAxisd(sign * candidate.hinge_angle[static_cast<int>(lower)],
                                        Eigen::Vector3d::UnitY())
                          .toRotationMatrix();
    tl.translation() = tu * lower_offset;
    for (size_t k = 0; k < local.size(); ++k) {
      const Eigen::Isometry3d& t = local[k].lower ? tl : tu;
      axes[k] = {t * local[k].a, t * local[k].b};
      spheres[k] = {0.5 * (axes[k].first + axes[k].second),
                    0.5 * (axes[k].second - axes[k].first).norm() + local[k].radius};
    }
    double cost = fixed_cost;
    taken = 0;
    for (size_t j = 0; j < active.size(); ++j) {
      const int i = active[j];
      const double e_limb = limb_residual(obs.points[i], below[j]);
      taken += is_lost[j] && e_limb <= fit.outlier_m;
      cost += std::min(HuberCost(std::min(rest[i], e_limb), delta), cap_cost);
    }
    for (const auto& [a, b] : axes)
      for (int i = 0; i < m; ++i) {
        const double t = m == 1 ? 0.5 : static_cast<double>(i) / (m - 1);
        double e = 0;
        Eigen::Vector3d grad;
        if (SilhouetteResidual(obs, a + t * (b - a), &e, &grad)) cost += 0.5 * w_sil * e * e;
      }
    return cost;
  };

  *current = cost_of(pose);
  int n_lost = 0;
  for (size_t j = 0; j < active.size(); ++j) {
    const int i = active[j];
    if (rest[i] > fit.outlier_m && limb_residual(obs.points[i]) > fit.outlier_m) {
      is_lost[j] = 1, ++n_lost;
      below[j] = std::max(below[j], std::nextafter(fit.outlier_m, 1.0));
    }
  }
  if (lost) *lost = n_lost;
  std::vector<ScoredHypothesis> scored;
  if (n_lost <= min_lost) return scored;
  const std::vector<LimbHypothesis> hypotheses = LimbHypotheses(pose, limb, limits, options);
  scored.reserve(hypotheses.size());
  ArticulatedPose candidate = pose;
  for (const LimbHypothesis& h : hypotheses) {
    candidate.local[static_cast<int>(upper)] = h.upper_local;
    candidate.hinge_angle[static_cast<int>(lower)] = h.hinge_angle;
    const double cost = cost_of(candidate);
    scored.push_back({cost, h, taken});
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

std::vector<ArticulatedPose> RankLimbHypotheses(const ArticulatedBody& body,
                                                const BodyObservation& obs,
                                                const BodyFitOptions& fit,
                                                const JointLimits& limits,
                                                const LimbSearchOptions& options,
                                                const ArticulatedPose& pose, Limb limb, int count) {
  options.Check();
  REENACT_CHECK(count >= 0, "count must be >= 0");
  std::vector<ArticulatedPose> ranked;
  if (obs.points.empty() || count == 0) return ranked;
  double current = 0;
  std::vector<ScoredHypothesis> scored =
      ScoreLimbHypotheses(body, obs, fit, limits, options, pose, limb, &current);
  std::stable_sort(
      scored.begin(), scored.end(),
      [](const ScoredHypothesis& a, const ScoredHypothesis& b) { return a.cost < b.cost; });
  std::vector<bool> used(kHeldLimbDirection + 1, false);
  for (const ScoredHypothesis& c : scored) {
    if (static_cast<int>(ranked.size()) >= count) break;
    if (used[c.h.direction]) continue;
    used[c.h.direction] = true;
    ranked.push_back(WithLimb(pose, limb, c.h, limits));
  }
  return ranked;
}

}  // namespace reenact::capture
