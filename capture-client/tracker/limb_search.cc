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

}  // namespace

void LimbSearchOptions::Check() const {
  REENACT_CHECK(cap_m > 0 && min_gain >= 0 && min_gain < 1, "cap_m > 0, 0 <= min_gain < 1");
}

int SearchLimbs(const ArticulatedBody& body, const BodyObservation& obs, const BodyFitOptions& fit,
                const JointLimits& limits, const LimbSearchOptions& options,
                ArticulatedPose* pose) {
  options.Check();
  if (obs.points.empty()) return 0;
  const double delta = fit.huber_m;
  const double cap_cost = HuberCost(options.cap_m, delta);
  const double w_sil = SilhouetteSampleWeight(obs, fit, static_cast<int>(body.capsules().size()));
  const int m = fit.samples_per_capsule;
  int changed = 0;
  const std::pair<S, S> limbs[] = {{S::kLeftUpperArm, S::kLeftForearm},
                                   {S::kRightUpperArm, S::kRightForearm},
                                   {S::kLeftThigh, S::kLeftShin},
                                   {S::kRightThigh, S::kRightShin}};
  std::vector<Eigen::Vector3d> dirs;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k)
        if (i || j || k) dirs.push_back(Eigen::Vector3d(i, j, k).normalized());
  std::vector<double> rest(obs.points.size());
  for (const auto& [upper, lower] : limbs) {
    const PosedBody3 posed = body.Pose(*pose);
    // Residual of every point to the held body.
    std::vector<LimbCapsule> local;
    std::fill(rest.begin(), rest.end(), std::numeric_limits<double>::infinity());
    for (const BodyCapsule& c : body.capsules()) {
      if (c.segment == upper || c.segment == lower) {
        local.push_back({c.segment == lower, c.a, c.b, c.radius});
        continue;
      }
      const Eigen::Isometry3d& t = posed.sensor_from_segment[static_cast<int>(c.segment)];
      const Eigen::Vector3d a = t * c.a, b = t * c.b;
      for (size_t i = 0; i < obs.points.size(); ++i)
        rest[i] = std::min(rest[i], AxisDistance(a, b, obs.points[i]) - c.radius);
    }
    const Eigen::Isometry3d& parent = posed.sensor_from_segment[SegmentParent(upper)];
    const Eigen::Vector3d joint = posed.sensor_from_segment[static_cast<int>(upper)].translation();
    const Eigen::Vector3d lower_offset = body.offset(lower);
    const double sign = lower == S::kLeftForearm || lower == S::kRightForearm ? -1.0 : 1.0;

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
      double cost = 0;
      std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> axes;
      std::vector<double> radii;
      for (const LimbCapsule& c : local) {
        const Eigen::Isometry3d& t = c.lower ? tl : tu;
        axes.emplace_back(t * c.a, t * c.b);
        radii.push_back(c.radius);
      }
      for (size_t i = 0; i < obs.points.size(); ++i) {
        double e = rest[i];
        for (size_t k = 0; k < axes.size(); ++k)
          e = std::min(e, AxisDistance(axes[k].first, axes[k].second, obs.points[i]) - radii[k]);
        cost += std::min(HuberCost(e, delta), cap_cost);
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

    const double current = cost_of(*pose);
    double best_cost = current;
    ArticulatedPose best = *pose;
    for (const Eigen::Vector3d& d_parent : dirs) {
      // The bone points along d; the segment's z axis points back to the joint.
      const Eigen::Vector3d z = -d_parent;
      Eigen::Vector3d x0 = Eigen::Vector3d::UnitX() - z.x() * z;
      if (x0.norm() < 1e-6) x0 = Eigen::Vector3d::UnitZ() - z.z() * z;
      x0.normalize();
      for (double angle : {0.0, 60.0, 110.0})
        for (int twist = 0; twist < (angle == 0 ? 1 : 4); ++twist) {
          const Eigen::Vector3d x = Eigen::AngleAxisd(twist * std::numbers::pi / 2, z) * x0;
          Eigen::Matrix3d local;
          local.col(0) = x;
          local.col(1) = z.cross(x);
          local.col(2) = z;
          ArticulatedPose candidate = *pose;
          candidate.local[static_cast<int>(upper)] = local;
          candidate.hinge_angle[static_cast<int>(lower)] = angle * std::numbers::pi / 180;
          ArticulatedBody::Clamp(&candidate, limits);
          const double c = cost_of(candidate);
          if (c < best_cost) best_cost = c, best = candidate;
        }
    }
    if (best_cost < (1 - options.min_gain) * current) {
      *pose = best;
      ++changed;
    }
  }
  return changed;
}

}  // namespace reenact::capture
