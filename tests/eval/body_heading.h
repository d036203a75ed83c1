#pragma once
// The heading of a skeleton, for the tracker's figures (tracker_eval.h).
//
// Forward: (l_shoulder - r_shoulder) x (neck - waist), the way the chest faces (the body
// frame's left x up = forward). The heading error of a tracked skeleton against the truth is
// the angle between their forwards projected on the floor (perpendicular to up): how far the
// tracked body is turned about the vertical from the true one, 0-180 degrees; above 90 the
// track faces more backwards than forwards (front and back confused, which a side view of a
// walk invites).
// Frames: any one frame for both skeletons and up (the tracker's figures use the sensor
// frame); up need not be unit.

#include <Eigen/Core>
#include <optional>

#include "common/skeleton/skeleton.h"

namespace reenact::eval {

// The unit forward above; nullopt when the shoulders coincide, the spine has no length, or
// the shoulder line runs along the spine.
std::optional<Eigen::Vector3d> BodyForward(const Skeleton& s);

// Degrees in [0, 180]; nullopt when either forward is undefined or (nearly, within 1 degree)
// parallel to up (a body lying face up shows no heading), or up is zero.
std::optional<double> HeadingErrorDeg(const Skeleton& tracked, const Skeleton& truth,
                                      const Eigen::Vector3d& up);

}  // namespace reenact::eval
