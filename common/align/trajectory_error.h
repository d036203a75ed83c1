#pragma once
// Absolute trajectory error (ATE; Sturm et al., TUM RGB-D benchmark): the RMSE of the sensor
// positions of an estimated trajectory after the transform that best aligns them to the
// ground truth (Umeyama, Eq. 17-24; rigid for RGB-D SLAM, similarity for monocular SLAM
// whose scale is unknown):
//   ATE = sqrt( (1/N) sum_i | p_gt_i - (s R p_est_i + t) |^2 )
// Poses are world_from_sensor; position i is the translation of pose i. Pairs are matched
// by index; AssociateByTimestamp matches two timestamped trajectories first.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <utility>
#include <vector>

#include "common/align/umeyama.h"
#include "common/geometry/similarity3.h"

namespace reenact {

enum class TrajectoryAlignment {
  kRigid,       // rotation + translation (scale fixed to 1)
  kSimilarity,  // rotation + translation + scale
};

struct TrajectoryErrorOptions {
  TrajectoryAlignment alignment = TrajectoryAlignment::kRigid;
};

struct TrajectoryErrorResult {
  // Why the alignment failed (kNone on success): fewer than 3 poses, non-finite positions,
  // or all estimated (or true) positions equal. A straight-line trajectory is accepted (its
  // ATE is well defined even though the rotation about the line is not).
  UmeyamaFailure failure = UmeyamaFailure::kNone;
  // ground-truth world from estimated world (the aligning transform).
  Sim3 truth_from_estimate;
  double ate_rmse_m = 0;  // the ATE, metres
  double mean_m = 0, median_m = 0, max_m = 0;
  std::vector<double> errors_m;  // per pose, metres, in input order

  bool ok() const { return failure == UmeyamaFailure::kNone; }
};

// ATE of estimated positions against true positions (same length; CHECK).
TrajectoryErrorResult AbsoluteTrajectoryError(
    const std::vector<Eigen::Vector3d>& truth_positions,
    const std::vector<Eigen::Vector3d>& estimated_positions,
    const TrajectoryErrorOptions& options = {});

// The same for world_from_sensor poses (their translations are compared).
TrajectoryErrorResult AbsoluteTrajectoryError(
    const std::vector<Eigen::Isometry3d>& truth_world_from_sensor,
    const std::vector<Eigen::Isometry3d>& estimated_world_from_sensor,
    const TrajectoryErrorOptions& options = {});

// Index pairs (truth, estimate) whose timestamps (seconds, each list ascending) differ by at
// most max_difference_s; each index used at most once, closest pairs first (as TUM's
// associate.py). Output sorted by estimate index. Preconditions (CHECK): max_difference_s >=
// 0 and finite, lists ascending and finite.
std::vector<std::pair<size_t, size_t>> AssociateByTimestamp(
    const std::vector<double>& truth_times_s, const std::vector<double>& estimate_times_s,
    double max_difference_s);

}  // namespace reenact
