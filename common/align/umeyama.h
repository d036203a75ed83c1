#pragma once
// Least-squares similarity between corresponding point sets (Umeyama 1991; thesis Eq. 17-24,
// the sensor-to-map alignment). Given pairs (a_i, b_i), i = 1..N, it finds b_from_a =
// (s, R, t) minimising
//   (1/N) sum_i || b_i - (s R a_i + t) ||^2                                     (Eq. 17)
// In the thesis's notation p_i = b_i (target) and q_i = a_i (source):
//   mu_a, mu_b the means; a'_i = a_i - mu_a, b'_i = b_i - mu_b                     (Eq. 18-19)
//   Sigma = (1/N) sum_i b'_i a'_i^T = U D V^T (SVD)                               (Eq. 20-21)
//   S = diag(1, 1, det(U V^T) < 0 ? -1 : 1)   (reflection correction)             (Eq. 22)
//   R = U S V^T                                                                   (Eq. 22)
//   s = trace(D S) / sigma_a^2, sigma_a^2 = (1/N) sum_i |a'_i|^2  (= sum b'^T R a' /
//       sum |R a'|^2 as the thesis writes it; 1 when the scale is not estimated)  (Eq. 23)
//   t = mu_b - s R mu_a  (Eq. 24 as printed omits the 1/N; these are the means)    (Eq. 24)
// The correction S makes R a rotation (det +1) even when the best orthogonal matrix is a
// reflection (mirrored data, or coplanar points whose SVD picks a mirrored third axis).
//
// Numerics: each set is first shifted by its first point, so that coordinates 1e4 m from
// the origin are summed as small offsets; the means and covariance are computed in that
// shifted frame and t is assembled at the end.
//
// Degenerate input is a value, not a crash: fewer than 3 pairs, a non-finite coordinate, all
// source (or target) points equal, or collinear points (rank Sigma < 2, where the rotation
// about the line is undetermined). Coplanar points are fine (rank 2 determines R).

#include <Eigen/Core>
#include <optional>
#include <string_view>
#include <vector>

#include "common/geometry/similarity3.h"

namespace reenact {

struct UmeyamaOptions {
  // Estimate the scale s (similarity); false fixes s = 1 (rigid).
  bool estimate_scale = true;
  // Collinear when D(1,1) <= collinear_tolerance * D(0,0) (singular values of Sigma);
  // in [0, 1), default 1e-10.
  double collinear_tolerance = 1e-10;
  // Accept collinear input and return one of the equally optimal transforms (the rotation
  // about the line is then arbitrary but the residual is minimal): for error measures such
  // as the ATE of a straight trajectory. Default false.
  bool allow_collinear = false;

  // Throws CheckError when a field is outside its range.
  void Check() const;
};

enum class UmeyamaFailure {
  kNone,
  kTooFewPoints,      // fewer than 3 pairs
  kNonFinite,         // a coordinate is NaN or infinite
  kCoincidentPoints,  // all source or all target points equal (no spread)
  kCollinearPoints,   // rank Sigma < 2: rotation about the line undetermined
};

// "none", "too_few_points", "non_finite", "coincident_points", "collinear_points".
std::string_view UmeyamaFailureName(UmeyamaFailure failure);

struct UmeyamaResult {
  std::optional<Sim3> b_from_a;  // set exactly when failure == kNone
  UmeyamaFailure failure = UmeyamaFailure::kNone;
  double rms_error = 0;  // sqrt of Eq. 17 at the solution, in b's units (0 on failure)

  bool ok() const { return b_from_a.has_value(); }
};

// b_from_a from pairs (points_in_a[i], points_in_b[i]). Precondition (CHECK): equal sizes
// and valid options.
UmeyamaResult Umeyama(const std::vector<Eigen::Vector3d>& points_in_a,
                      const std::vector<Eigen::Vector3d>& points_in_b,
                      const UmeyamaOptions& options = {});

}  // namespace reenact
