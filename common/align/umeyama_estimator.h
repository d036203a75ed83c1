#pragma once
// Umeyama (Eq. 17-24) as a RANSAC estimator (common/estimate/ransac.h) for 3D-3D
// correspondences with outliers: a sample is a pair (point in a, point in b), the model is
// b_from_a, the residual is the distance |b - b_from_a * a| in b's units.

#include <Eigen/Core>
#include <vector>

#include "common/align/umeyama.h"
#include "common/geometry/similarity3.h"

namespace reenact {

struct UmeyamaEstimator {
  struct Sample {
    Eigen::Vector3d point_in_a;
    Eigen::Vector3d point_in_b;
  };
  using Model = Sim3;  // b_from_a
  static constexpr int kMinSampleSize = 3;

  UmeyamaOptions options;

  // One model, or none when the samples are degenerate (collinear, coincident, ...).
  std::vector<Sim3> Estimate(const std::vector<Sample>& samples) const {
    std::vector<Eigen::Vector3d> a, b;
    a.reserve(samples.size());
    b.reserve(samples.size());
    for (const Sample& s : samples) {
      a.push_back(s.point_in_a);
      b.push_back(s.point_in_b);
    }
    const UmeyamaResult fit = Umeyama(a, b, options);
    if (!fit.ok()) return {};
    return {*fit.b_from_a};
  }

  std::vector<double> Residuals(const Sim3& b_from_a, const std::vector<Sample>& samples) const {
    std::vector<double> r;
    r.reserve(samples.size());
    for (const Sample& s : samples) r.push_back((s.point_in_b - b_from_a * s.point_in_a).norm());
    return r;
  }
};

}  // namespace reenact
