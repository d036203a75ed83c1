#include "common/align/trajectory_error.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "common/error/check.h"

namespace reenact {

TrajectoryErrorResult AbsoluteTrajectoryError(
    const std::vector<Eigen::Vector3d>& truth_positions,
    const std::vector<Eigen::Vector3d>& estimated_positions,
    const TrajectoryErrorOptions& options) {
  REENACT_CHECK(truth_positions.size() == estimated_positions.size(),
                "trajectories must have the same number of poses");
  UmeyamaOptions umeyama;
  umeyama.estimate_scale = options.alignment == TrajectoryAlignment::kSimilarity;
  umeyama.allow_collinear = true;
  const UmeyamaResult fit = Umeyama(estimated_positions, truth_positions, umeyama);

  TrajectoryErrorResult result;
  result.failure = fit.failure;
  if (!fit.ok()) return result;
  result.truth_from_estimate = *fit.b_from_a;
  const size_t n = truth_positions.size();
  double sum = 0, sum_sq = 0;
  result.errors_m.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    const double e =
        (truth_positions[i] - result.truth_from_estimate * estimated_positions[i]).norm();
    result.errors_m.push_back(e);
    sum += e;
    sum_sq += e * e;
    result.max_m = std::max(result.max_m, e);
  }
  result.ate_rmse_m = std::sqrt(sum_sq / static_cast<double>(n));
  result.mean_m = sum / static_cast<double>(n);
  std::vector<double> sorted = result.errors_m;
  std::sort(sorted.begin(), sorted.end());
  result.median_m = n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  return result;
}

TrajectoryErrorResult AbsoluteTrajectoryError(
    const std::vector<Eigen::Isometry3d>& truth_world_from_sensor,
    const std::vector<Eigen::Isometry3d>& estimated_world_from_sensor,
    const TrajectoryErrorOptions& options) {
  std::vector<Eigen::Vector3d> truth, estimate;
  truth.reserve(truth_world_from_sensor.size());
  estimate.reserve(estimated_world_from_sensor.size());
  for (const auto& p : truth_world_from_sensor) truth.push_back(p.translation());
  for (const auto& p : estimated_world_from_sensor) estimate.push_back(p.translation());
  return AbsoluteTrajectoryError(truth, estimate, options);
}

std::vector<std::pair<size_t, size_t>> AssociateByTimestamp(
    const std::vector<double>& truth_times_s, const std::vector<double>& estimate_times_s,
    double max_difference_s) {
  REENACT_CHECK(std::isfinite(max_difference_s) && max_difference_s >= 0,
                "max_difference_s must be >= 0 and finite");
  for (const auto* times : {&truth_times_s, &estimate_times_s}) {
    REENACT_CHECK(
        std::all_of(times->begin(), times->end(), [](double t) { return std::isfinite(t); }),
        "timestamps must be finite");
    REENACT_CHECK(std::is_sorted(times->begin(), times->end()), "timestamps must be ascending");
  }
  // Candidates: for each estimate, every truth within the window (a window is short).
  std::vector<std::tuple<double, size_t, size_t>> candidates;  // (|dt|, truth, estimate)
  for (size_t j = 0; j < estimate_times_s.size(); ++j) {
    const double t = estimate_times_s[j];
    auto it = std::lower_bound(truth_times_s.begin(), truth_times_s.end(), t - max_difference_s);
    for (; it != truth_times_s.end() && *it <= t + max_difference_s; ++it)
      candidates.emplace_back(std::abs(*it - t), static_cast<size_t>(it - truth_times_s.begin()),
                              j);
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<bool> truth_used(truth_times_s.size()), estimate_used(estimate_times_s.size());
  std::vector<std::pair<size_t, size_t>> pairs;
  for (const auto& [dt, i, j] : candidates) {
    if (truth_used[i] || estimate_used[j]) continue;
    truth_used[i] = estimate_used[j] = true;
    pairs.emplace_back(i, j);
  }
  std::sort(pairs.begin(), pairs.end(),
            [](const auto& x, const auto& y) { return x.second < y.second; });
  return pairs;
}

}  // namespace reenact
