#include "capture-client/segment/floor_plane.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "common/estimate/ransac.h"

namespace reenact::capture {

Plane3 Plane3::Transformed(const Eigen::Isometry3d& b_from_a) const {
  Plane3 out;
  out.normal = b_from_a.linear() * normal;
  out.offset = offset + out.normal.dot(b_from_a.translation());
  return out;
}

double FloorResidual(const Plane3& plane, const Eigen::Vector3d& p,
                     const DepthTolerance& tolerance) {
  const double across = std::abs(plane.normal.dot(p));
  return std::abs(plane.SignedDistance(p)) /
         (tolerance.base_m + tolerance.per_z2 * std::max(0.0, p.z()) * across);
}

std::vector<Plane3> FloorPlaneEstimator::Estimate(
    const std::vector<Eigen::Vector3d>& samples) const {
  if (samples.size() < 3) return {};
  Eigen::Vector3d normal;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  if (samples.size() == 3) {
    mean = (samples[0] + samples[1] + samples[2]) / 3;
    const Eigen::Vector3d e1 = samples[1] - samples[0], e2 = samples[2] - samples[0];
    normal = e1.cross(e2);
    const double scale = e1.squaredNorm() * e2.squaredNorm();
    if (!(normal.squaredNorm() > 1e-6 * scale) || scale <= 0) return {};  // collinear
    normal.normalize();
  } else {
    // Weighted by the inverse depth noise variance: near points, which see the floor's
    // height best, outweigh far ones (and far clutter that touches the floor, e.g. the foot
    // of a wall, pulls less).
    double total = 0;
    std::vector<double> weights;
    weights.reserve(samples.size());
    for (const auto& s : samples) {
      const double tol = tolerance.At(std::max(0.0, s.z()));
      weights.push_back(1 / (tol * tol));
      total += weights.back();
      mean += weights.back() * s;
    }
    mean /= total;
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (size_t i = 0; i < samples.size(); ++i)
      scatter += weights[i] * (samples[i] - mean) * (samples[i] - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
    if (!(eig.eigenvalues()(1) > 1e-9 * eig.eigenvalues()(2))) return {};
    normal = eig.eigenvectors().col(0);
  }
  if (normal.dot(up) < 0) normal = -normal;
  if (normal.dot(up) < min_up_cosine) return {};
  return {Plane3{normal, normal.dot(mean)}};
}

std::vector<double> FloorPlaneEstimator::Residuals(
    const Plane3& plane, const std::vector<Eigen::Vector3d>& samples) const {
  std::vector<double> r;
  r.reserve(samples.size());
  for (const auto& s : samples) r.push_back(FloorResidual(plane, s, tolerance));
  return r;
}

std::optional<FloorGuess> GuessFloor(const Skeleton& skeleton, const Eigen::Vector3d& up) {
  struct Usual {
    Joint joint;
    double height;
  };
  static constexpr Usual kUsual[] = {{Joint::kLeftFoot, 0.08}, {Joint::kRightFoot, 0.08},
                                     {Joint::kLeftKnee, 0.5},  {Joint::kRightKnee, 0.5},
                                     {Joint::kLeftHip, 0.9},   {Joint::kRightHip, 0.9},
                                     {Joint::kWaist, 0.95}};
  std::optional<FloorGuess> best;
  for (const Usual& u : kUsual) {
    if (!skeleton.Has(u.joint)) continue;
    const Eigen::Vector3d& p = skeleton[u.joint];
    const double height = up.dot(p) - u.height;
    if (!best || height < best->height) best = FloorGuess{height, p - u.height * up};
  }
  if (!best) return std::nullopt;
  // Under the feet: the mean of the present feet (else of whatever gave the floor), dropped
  // onto the guessed floor height.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  int n = 0;
  for (Joint j : {Joint::kLeftFoot, Joint::kRightFoot})
    if (skeleton.Has(j)) centre += skeleton[j], ++n;
  if (n > 0) {
    centre /= n;
    best->under_feet = centre + (best->height - up.dot(centre)) * up;
  }
  return best;
}

bool IsFloorCandidate(const Eigen::Vector3d& p, const Eigen::Vector3d& up, const FloorGuess& guess,
                      const PersonSegmentOptions& options) {
  const Eigen::Vector3d d = p - guess.under_feet;
  const double along = up.dot(d);
  if (std::abs(along) > options.floor_search_band_m) return false;
  const double across2 = d.squaredNorm() - along * along;
  return across2 <= options.floor_search_radius_m * options.floor_search_radius_m;
}

bool OnOrUnderFloor(const Plane3& floor, const Eigen::Vector3d& p,
                    const DepthTolerance& clearance) {
  const double z = std::max(0.0, p.z());
  return floor.SignedDistance(p) <
         clearance.base_m + clearance.per_z2 * z * std::abs(floor.normal.dot(p));
}

FloorFit ScoreFloorPlane(const Plane3& plane, const std::vector<Eigen::Vector3d>& candidates,
                         const PersonSegmentOptions& options) {
  FloorFit fit;
  fit.plane = plane;
  fit.candidates = static_cast<int>(candidates.size());
  for (const auto& p : candidates) fit.inliers += FloorResidual(plane, p, options.floor_fit) <= 1;
  fit.inlier_ratio = candidates.empty() ? 0.0 : static_cast<double>(fit.inliers) / fit.candidates;
  return fit;
}

std::optional<FloorFit> FitFloorPlane(const std::vector<Eigen::Vector3d>& candidates,
                                      const Eigen::Vector3d& up,
                                      const PersonSegmentOptions& options) {
  if (static_cast<int>(candidates.size()) < options.floor_min_inliers) return std::nullopt;
  FloorPlaneEstimator estimator;
  estimator.up = up.normalized();
  estimator.min_up_cosine = std::cos(options.floor_max_tilt_deg * std::numbers::pi / 180);
  estimator.tolerance = options.floor_fit;
  RansacOptions ro;
  ro.max_error = 1.0;
  ro.max_iterations = options.floor_max_trials;
  ro.seed = options.floor_seed;
  ro.local_optimization_rounds = 2;
  ro.final_refit = true;
  const auto result = Ransac(estimator, candidates, ro);
  if (!result.success || static_cast<int>(result.inliers.size()) < options.floor_min_inliers)
    return std::nullopt;
  // Tightening: refit on the points within half the tolerance, a few times. RANSAC's
  // consensus counts every point within the tolerance alike, so a plane tilted towards the
  // foot of a wall (which touches the floor) can hold a few more; the tight refits follow
  // the many floor points instead.
  Plane3 plane = result.model;
  std::vector<Eigen::Vector3d> tight;
  for (int round = 0; round < 3; ++round) {
    tight.clear();
    for (const auto& p : candidates)
      if (FloorResidual(plane, p, options.floor_fit) <= 0.5) tight.push_back(p);
    if (static_cast<int>(tight.size()) < options.floor_min_inliers) break;
    const auto refined = estimator.Estimate(tight);
    if (refined.empty()) break;
    plane = refined.front();
  }
  const FloorFit fit = ScoreFloorPlane(plane, candidates, options);
  if (fit.inliers < options.floor_min_inliers || fit.inlier_ratio < options.floor_min_inlier_ratio)
    return std::nullopt;
  return fit;
}

}  // namespace reenact::capture
