#pragma once
// The floor under a person: a plane fitted by RANSAC (common/estimate/ransac.h) to depth
// points near the floor height that the skeleton implies, constrained to be roughly
// perpendicular to the body's up axis. All points in the sensor frame (OpenCV axes, metres).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "capture-client/segment/segment_options.h"
#include "common/skeleton/skeleton.h"

namespace reenact::capture {

// The plane normal . x = offset, unit normal, in the frame its owner states.
struct Plane3 {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0;

  double SignedDistance(const Eigen::Vector3d& p) const { return normal.dot(p) - offset; }
  // The same plane in frame b, given b_from_a and this plane in frame a.
  Plane3 Transformed(const Eigen::Isometry3d& b_from_a) const;
};

// Distance of p to the plane over the depth noise across it:
//   |n . p - offset| / (tolerance.base_m + tolerance.per_z2 z |n . p|),  z = p.z()
// (a depth error dz moves p along its ray by dz |p| / z, across the plane by dz |n . p| / z;
// the Kinect's dz grows with z^2).
double FloorResidual(const Plane3& plane, const Eigen::Vector3d& p,
                     const DepthTolerance& tolerance);

// RANSAC estimator of the floor. Model: a plane whose normal points along `up` (unit). Three
// points give the plane through them; more give the total-least-squares plane weighted by
// 1 / tolerance.At(z)^2 (the inverse depth noise variance). Draws that are
// (nearly) collinear, or whose normal is more than max_tilt from up, give no model.
// Residual: FloorResidual (a point is an inlier when it is <= 1).
struct FloorPlaneEstimator {
  using Sample = Eigen::Vector3d;
  using Model = Plane3;
  static constexpr int kMinSampleSize = 3;

  Eigen::Vector3d up = -Eigen::Vector3d::UnitY();
  double min_up_cosine = 0.766;  // cos(max_tilt)
  DepthTolerance tolerance{0.01, 0.005};

  std::vector<Plane3> Estimate(const std::vector<Eigen::Vector3d>& samples) const;
  std::vector<double> Residuals(const Plane3& plane,
                                const std::vector<Eigen::Vector3d>& samples) const;
};

// Where the floor should be, from the skeleton: its height along up (up . x of a floor point)
// and the point on it under the feet.
struct FloorGuess {
  double height = 0;
  Eigen::Vector3d under_feet = Eigen::Vector3d::Zero();
};

// From the lowest leg joints: each present foot, knee, hip or the waist implies a floor at
// its height minus its usual height on a standing adult (0.08, 0.5, 0.9, 0.95 m); the
// lowest implied floor wins (a kicking leg lifts its own joints, not the floor). nullopt
// when no leg joint and no waist are present (an upper-body skeleton).
std::optional<FloorGuess> GuessFloor(const Skeleton& skeleton_in_sensor, const Eigen::Vector3d& up);

// Whether a point is a floor candidate: within the options' search band of the guessed floor
// height and within their search radius of the point under the feet (across up).
bool IsFloorCandidate(const Eigen::Vector3d& p, const Eigen::Vector3d& up, const FloorGuess& guess,
                      const PersonSegmentOptions& options);

struct FloorFit {
  Plane3 plane;     // sensor frame, normal along up
  int inliers = 0;  // candidates with FloorResidual(plane, p, floor_fit) <= 1
  int candidates = 0;
  double inlier_ratio = 0;
};

// The dominant floor among the candidates (normal within floor_max_tilt_deg of up, at least
// floor_min_inliers inliers making at least floor_min_inlier_ratio of the candidates),
// refined on its inliers; nullopt when there is none.
// Deterministic for the options' seed.
std::optional<FloorFit> FitFloorPlane(const std::vector<Eigen::Vector3d>& candidates,
                                      const Eigen::Vector3d& up,
                                      const PersonSegmentOptions& options);

// Whether a point (sensor frame, depth z = p.z()) is on or under the floor: its height above
// it is below clearance.base_m + clearance.per_z2 z^2 |n . p| / z. A depth error dz moves
// the point along its ray by dz |p| / z, i.e. across the floor (normal n) by dz |n . p| / z;
// see PersonSegmentOptions::floor_clearance.
bool OnOrUnderFloor(const Plane3& floor, const Eigen::Vector3d& p, const DepthTolerance& clearance);

// How well a known plane fits this frame's candidates (inliers: FloorResidual <= 1).
FloorFit ScoreFloorPlane(const Plane3& plane, const std::vector<Eigen::Vector3d>& candidates,
                         const PersonSegmentOptions& options);

}  // namespace reenact::capture
