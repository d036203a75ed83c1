#pragma once
// Smooths the tracked viewer pose over time: a constant-velocity Kalman filter on the pose,
// fed with each frame's refined pose and its information matrix (vision/pose/
// pose_refinement.h). A hand-held camera moves smoothly at 30 Hz, while a single frame's pose
// is uncertain mostly along one direction: against a far wall, a sideways shift and a turn
// that keeps the wall in place look alike, and their combination jumps by centimetres from
// frame to frame. The information matrix says which directions a frame pins down; the filter
// takes those from the frame and the rest from the motion so far.
//
// Pose and update as in vision/pose/observation_model.h: viewer_from_world T, perturbed on
// the left, T <- U(delta) T with delta = (v, w), U(delta) = [ExpSo3(w) | v] (translation v in
// metres, rotation vector w in radians). State: T and a per-frame velocity xi (the same
// parametrisation: T_{k+1} = U(xi) T_k), with the covariance P of their 12-dimensional error.
//
//   predict:  T- = U(xi) T,  xi- = xi,  P- = F P F^T + G Qa G^T,  F = [I I; 0 I],
//             G = [I/2; I], Qa = diag(sigma_t^2 I3, sigma_r^2 I3) (acceleration per frame^2)
//   update:   y = delta(T_meas T-^-1),  S = P-_pose + H^-1,  K = P- [I 0]^T S^-1,
//             (delta_T, delta_xi) = K y,  T = U(delta_T) T-,  xi = xi- + delta_xi,
//             P = (I - K [I 0]) P-
// A measurement whose Mahalanobis distance y^T S^-1 y exceeds gate_chi2 (the camera jumped,
// or the frame's pose is wrong) restarts the filter at the measurement, as does the first.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

namespace reenact::viewer {

struct PoseSmootherOptions {
  // Standard deviation of the camera's acceleration, per frame squared: metres (> 0) and
  // degrees (> 0). Defaults 5 mm and 0.5 degrees: a hand that shakes by 3 mm / 0.3 degrees at
  // 3 Hz, or pans up to 90 degrees/s within a third of a second, at 30 Hz.
  double acceleration_m = 0.005;
  double acceleration_deg = 0.5;
  // Chi-square with 6 degrees of freedom past which a measurement restarts the filter (> 0).
  // Default 22.46 (99.9%).
  double gate_chi2 = 22.46;

  void Check() const;  // throws CheckError when out of range
};

class PoseSmoother {
 public:
  explicit PoseSmoother(const PoseSmootherOptions& options = {});

  // The pose predicted for the next frame (constant velocity); nullopt before the first
  // measurement and after Reset().
  std::optional<Eigen::Isometry3d> Predict() const;

  // One frame's measured viewer_from_world with its 6x6 information matrix (inverse
  // covariance of delta; symmetric, positive semi-definite, may be rank deficient: a small
  // floor keeps it invertible). Returns the smoothed pose. A non-finite measurement restarts
  // nothing and returns the prediction (or the measurement when there is none).
  Eigen::Isometry3d Update(const Eigen::Isometry3d& measured,
                           const Eigen::Matrix<double, 6, 6>& information);

  // Forgets the track (the camera was lost or relocalised from scratch).
  void Reset() { pose_.reset(); }

  bool restarted() const { return restarted_; }  // the last Update restarted the filter

 private:
  using Matrix12 = Eigen::Matrix<double, 12, 12>;
  void Restart(const Eigen::Isometry3d& measured, const Eigen::Matrix<double, 6, 6>& covariance);

  PoseSmootherOptions options_;
  std::optional<Eigen::Isometry3d> pose_;
  Eigen::Matrix<double, 6, 1> velocity_ = Eigen::Matrix<double, 6, 1>::Zero();
  Matrix12 covariance_ = Matrix12::Identity();
  bool restarted_ = false;
};

// delta with U(delta) a = b (see above): v = t_b - R t_a, w = log(R_b R_a^T).
Eigen::Matrix<double, 6, 1> PoseDelta(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

}  // namespace reenact::viewer
