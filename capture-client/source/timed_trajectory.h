#pragma once
// A trajectory sampled at known times (a motion-capture ground truth), read at any time in
// between: position linear, rotation by spherical linear interpolation (slerp, the shortest
// arc) between the two samples around t,
//   s = (t - t_a) / (t_b - t_a),  p(t) = (1 - s) p_a + s p_b,  q(t) = slerp(q_a, q_b, s).
// The interpolation error is that of a straight chord between samples: for motion with
// speed v and acceleration a over a sample gap dt, at most a dt^2 / 8 in position (about
// 0.1 mm at 100 Hz and 1 m/s^2), and likewise for the angle.

#include <Eigen/Geometry>
#include <optional>
#include <vector>

namespace reenact::capture {

struct TimedPose {
  double timestamp_s = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();            // world frame, metres
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // unit, world_from_sensor
};

// world_from_sensor at time t from samples in ascending time order (CHECK: ascending and
// finite). nullopt when t is not finite, there are no samples, t lies outside
// [first, last] sample time, or the two samples around t are more than max_gap_s apart
// (a gap in the recording: interpolating across it would invent motion). At a sample's
// exact time, that sample; two samples at one time give the first.
std::optional<Eigen::Isometry3d> InterpolatePose(const std::vector<TimedPose>& samples, double t,
                                                 double max_gap_s);

}  // namespace reenact::capture
