#include "common/align/umeyama.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>

#include "common/error/check.h"

namespace reenact {
namespace {

UmeyamaResult Failed(UmeyamaFailure failure) {
  UmeyamaResult r;
  r.failure = failure;
  return r;
}

}  // namespace

void UmeyamaOptions::Check() const {
  REENACT_CHECK(collinear_tolerance >= 0 && collinear_tolerance < 1,
                "collinear_tolerance must be in [0, 1)");
}

std::string_view UmeyamaFailureName(UmeyamaFailure failure) {
  switch (failure) {
    case UmeyamaFailure::kNone:
      return "none";
    case UmeyamaFailure::kTooFewPoints:
      return "too_few_points";
    case UmeyamaFailure::kNonFinite:
      return "non_finite";
    case UmeyamaFailure::kCoincidentPoints:
      return "coincident_points";
    case UmeyamaFailure::kCollinearPoints:
      return "collinear_points";
  }
  return "unknown";
}

UmeyamaResult Umeyama(const std::vector<Eigen::Vector3d>& points_in_a,
                      const std::vector<Eigen::Vector3d>& points_in_b,
                      const UmeyamaOptions& options) {
  options.Check();
  REENACT_CHECK(points_in_a.size() == points_in_b.size(),
                "Umeyama: point sets must have the same size");
  const size_t n = points_in_a.size();
  if (n < 3) return Failed(UmeyamaFailure::kTooFewPoints);
  for (size_t i = 0; i < n; ++i)
    if (!points_in_a[i].allFinite() || !points_in_b[i].allFinite())
      return Failed(UmeyamaFailure::kNonFinite);

  // Shifted frame: offsets from the first point of each set.
  const Eigen::Vector3d origin_a = points_in_a[0], origin_b = points_in_b[0];
  Eigen::Vector3d mean_a = Eigen::Vector3d::Zero(), mean_b = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    mean_a += points_in_a[i] - origin_a;
    mean_b += points_in_b[i] - origin_b;
  }
  mean_a /= static_cast<double>(n);
  mean_b /= static_cast<double>(n);

  Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
  double var_a = 0, var_b = 0;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d a = points_in_a[i] - origin_a - mean_a;
    const Eigen::Vector3d b = points_in_b[i] - origin_b - mean_b;
    sigma += b * a.transpose();
    var_a += a.squaredNorm();
    var_b += b.squaredNorm();
  }
  sigma /= static_cast<double>(n);
  var_a /= static_cast<double>(n);
  var_b /= static_cast<double>(n);
  if (!(var_a > 0) || !(var_b > 0)) return Failed(UmeyamaFailure::kCoincidentPoints);

  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d d = svd.singularValues();
  if (!(d(1) > options.collinear_tolerance * d(0)) && !options.allow_collinear)
    return Failed(UmeyamaFailure::kCollinearPoints);
  if (!(d(0) > 0)) return Failed(UmeyamaFailure::kCollinearPoints);

  const Eigen::Matrix3d& u = svd.matrixU();
  const Eigen::Matrix3d& v = svd.matrixV();
  Eigen::Vector3d s_diag(1, 1, 1);
  if ((u * v.transpose()).determinant() < 0) s_diag(2) = -1;
  const Eigen::Matrix3d r = u * s_diag.asDiagonal() * v.transpose();
  const double trace_ds = d.dot(s_diag);
  const double scale = options.estimate_scale ? trace_ds / var_a : 1.0;
  if (!(scale > 0)) return Failed(UmeyamaFailure::kCollinearPoints);

  // t = mu_b - s R mu_a with mu = origin + shifted mean.
  const Eigen::Vector3d t = (origin_b + mean_b) - scale * (r * (origin_a + mean_a));

  // Eq. 17 at the optimum: sigma_b^2 - 2 s tr(DS) + s^2 sigma_a^2, evaluated directly on the
  // centred points, which does not cancel catastrophically when the fit is good.
  double sum_sq = 0;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d a = points_in_a[i] - origin_a - mean_a;
    const Eigen::Vector3d b = points_in_b[i] - origin_b - mean_b;
    sum_sq += (b - scale * (r * a)).squaredNorm();
  }

  UmeyamaResult result;
  result.b_from_a = Sim3(scale, r, t);
  result.rms_error = std::sqrt(sum_sq / static_cast<double>(n));
  return result;
}

}  // namespace reenact
