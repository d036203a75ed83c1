#pragma once
// The measurement model shared by pose refinement and local bundle adjustment: a map point
// seen by an RGB-D frame gives a keypoint (pixel) and, where the depth image has a reading,
// a depth. Residuals are whitened (divided by their standard deviation) so that pixel and
// depth terms add up in one unitless cost:
//
//   X = (X, Y, Z) = sensor_from_world * point_in_world      (camera frame, metres)
//   r_u = fx (X / Z - x_n) / sigma_px,  r_v = fy (Y / Z - y_n) / sigma_px
//   r_d = (Z - d) / sigma_d(d)                               (only when d > 0)
//   sigma_px = pixel_sigma_px * scale_factor^octave          (the ORB pyramid level)
//   sigma_d = depth_sigma_1m_m * d^2 * (octave_scales_depth ? scale_factor^octave : 1)
// with (x_n, y_n) the keypoint's undistorted normalised image coordinates and d the depth
// reading along the optical axis (metres). sigma_d stands for the error of the depth *at a
// keypoint*: on real data that is dominated not by the sensor's axial noise (about 2 mm at
// 1 m for a Kinect v1, Nguyen, Izadi and Lovell 2012) but by how colour and depth disagree:
// imperfect registration, exposure at different instants and rolling shutters while the
// camera moves, corners on depth edges. On TUM RGB-D fr1_rpy, keypoints matched between
// consecutive frames, with the pose fitted to their reprojections alone, have depths that
// disagree with the prediction by 1-7 cm between the 10th and 90th percentiles at 1-2 m
// (measured while building this). It grows with d^2 as any disparity-based depth does.
// The default, 5 cm at 1 m against 2 px for a keypoint, weighs depth as ORB-SLAM2's RGB-D
// mode does (a virtual stereo disparity bf / d with sigma of one pixel at level 0 and
// bf = 40: sigma_d = d^2 / 40 m per pixel of keypoint sigma).
//
// The squared norm |r|^2 is chi-square distributed with 2 (no depth) or 3 degrees of freedom
// for inliers; outliers are rejected at the 95% quantiles (5.991 and 7.815), and the cost of
// an observation is Huber's on |r| with threshold sqrt of that quantile.
//
// Pose perturbations are left-multiplied on sensor_from_world: T <- Exp(delta) T with
// delta = (translation, rotation vector), so that d X / d delta = [I | -[X]x].

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace reenact::vision {

struct ObservationNoise {
  // Keypoint standard deviation at pyramid level 0, pixels; > 0. Default 2 (on real data
  // keypoints move by rolling shutter and motion blur as much as by detection noise).
  double pixel_sigma_px = 2.0;
  // ORB pyramid scale factor (> 1): sigma grows by it per level. Default 1.2.
  double scale_factor = 1.2;
  // Depth standard deviation at 1 m, metres (grows with d^2); > 0. Default 0.05.
  double depth_sigma_1m_m = 0.05;
  // Whether sigma_d grows with the keypoint's pyramid level as sigma_px does. Default true.
  bool octave_scales_depth = true;

  void Check() const;
  double PixelSigma(int octave) const;
  double DepthSigma(double depth_m, int octave) const;
};

// One keypoint observation in a frame.
struct KeypointObservation {
  Eigen::Vector2d normalized = Eigen::Vector2d::Zero();  // undistorted (x_n, y_n)
  double depth_m = 0;  // depth reading at the keypoint, metres; 0 = none
  int octave = 0;      // ORB pyramid level, >= 0
};

inline constexpr double kChi2Dof2 = 5.991;  // 95% quantile, 2 degrees of freedom
inline constexpr double kChi2Dof3 = 7.815;  // 95% quantile, 3 degrees of freedom

struct ObservationResidual {
  bool valid = false;  // false when the point is not in front of the camera (Z <= 1 cm)
  int dof = 2;         // 2, or 3 with a depth reading
  Eigen::Vector3d r = Eigen::Vector3d::Zero();  // whitened residual; r(2) = 0 when dof == 2
  Eigen::Matrix3d d_r_d_point = Eigen::Matrix3d::Zero();  // d r / d X (camera frame)

  double Chi2() const { return r.squaredNorm(); }
  double Chi2Threshold() const { return dof == 3 ? kChi2Dof3 : kChi2Dof2; }
  bool IsInlier() const { return valid && Chi2() <= Chi2Threshold(); }
  // Huber weight w(|r|) = min(1, delta / |r|) for IRLS, delta = sqrt(Chi2Threshold()).
  double HuberWeight() const;
  // Huber cost rho(|r|): |r|^2 / 2 inside delta, delta (|r| - delta / 2) outside.
  double HuberCost() const;
};

// Residual and Jacobian of one observation of point_in_camera. fx, fy in pixels.
ObservationResidual EvaluateObservation(const Eigen::Vector3d& point_in_camera,
                                        const KeypointObservation& observation, double fx,
                                        double fy, const ObservationNoise& noise);

// d X / d delta for the left perturbation (3 x 6: translation, rotation).
Eigen::Matrix<double, 3, 6> PointJacobianWrtPose(const Eigen::Vector3d& point_in_camera);

// Exp(delta) * sensor_from_world, delta = (translation (m), rotation vector (rad)).
Eigen::Isometry3d ApplyPoseUpdate(const Eigen::Matrix<double, 6, 1>& delta,
                                  const Eigen::Isometry3d& sensor_from_world);

}  // namespace reenact::vision
