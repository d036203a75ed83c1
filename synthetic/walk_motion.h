#pragma once
// A procedural walk of the synthetic subject (body_model.h): a gait cycle (legs and arms
// swinging) driven by the distance walked along a circle, with a smooth start and stop.
//
// Gait, per leg, as a function of its phase p in [0, 1) (p = 0 at heel strike; the right leg
// half a cycle behind the left), angles in degrees scaled by the gait amplitude a in [0, 1]:
//   hip flexion    7.5 + 17.5 cos(2 pi p)           (leg forward at heel strike, back at 0.5)
//   knee flexion   15 b(p; 0.15, 0.08) + 60 b(p; 0.72, 0.11)   (loading bump, swing bump)
//   ankle          10 b(p; 0.6, 0.08)               (push-off)
// with b(p; c, w) = exp(-(d / w)^2), d the wrapped distance from p to c. Arms swing against
// the legs: shoulder flexion 15 cos(2 pi (p + 0.5)) of the same side, elbows 15 + 10 * the
// forward share of the swing, abduction 7 (clear of the hips); a slight spine counter-twist.
//
// Path: a circle of radius_m walked counter-clockwise (seen from above), starting at the
// world origin facing world -y (so the centre is at (radius_m, 0)), the body turned along the
// path's tangent. Speed v(t) = v_max s(t) with s rising smoothly over the first ramp_s seconds
// and falling over the last ramp_s; v_max makes the walk exactly one full circle. The gait
// phase advances by distance / stride_m, the amplitude a = v / v_max (standing still at the
// ends). Feet are not pinned to the floor (the waist height follows body_model.h's rule).

#include <Eigen/Core>
#include <vector>

#include "synthetic/body_model.h"

namespace reenact::capture {

struct CircleWalkOptions {
  double duration_s = 7.0;  // > 2 * ramp_s
  double radius_m = 0.8;    // > 0
  double stride_m = 1.0;    // distance per full gait cycle (two steps), > 0
  double ramp_s = 0.8;      // start and stop, >= 0

  // Throws CheckError when a field is out of range.
  void Check() const;
};

// The gait pose at phase p (any real; taken modulo 1) with amplitude a in [0, 1]; root_xy and
// root_yaw are zero.
BodyPose WalkCyclePose(double phase, double amplitude);

// One pose per frame at frame_rate_hz (> 0): frames 0 .. round(duration_s * rate) - 1.
std::vector<BodyPose> CircleWalk(const CircleWalkOptions& options, double frame_rate_hz);

}  // namespace reenact::capture
