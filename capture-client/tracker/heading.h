#pragma once
// The body's heading when the subject has not shown the calibration pose (issue 8): an upright
// person in any heading, seen in depth, where front and back give nearly the same silhouette
// and surface (most of all in a side view).
//  - Candidates: count headings evenly spaced about the floor's up, starting at "facing the
//    sensor"; each one an upright start pose (UprightPose) that the tracker fits, the fit
//    residual choosing among them.
//  - Travel: a walking subject faces the way it goes. TravelDirection keeps the root's path
//    over a window of frames; once the root has moved at least min_distance_m across the floor
//    within the window, its direction (first to last position, projected on the floor) is the
//    front. The tracker uses it to settle the front/back ambiguity: a fitted forward more than
//    acos(flip_cos) away from the travel direction is re-fitted facing the travel direction.
// Frames: the sensor frame (OpenCV axes, metres); up is the floor's unit normal.

#include <Eigen/Core>
#include <deque>
#include <optional>
#include <vector>

#include "capture-client/tracker/articulated_body.h"

namespace reenact::capture {

// count (>= 1) unit headings across `up`, the first along toward_sensor projected on the
// floor, turning about up by 2 pi / count. Empty when toward_sensor is (nearly) parallel to up
// or either vector is zero.
std::vector<Eigen::Vector3d> CandidateHeadings(const Eigen::Vector3d& up,
                                               const Eigen::Vector3d& toward_sensor, int count);

// The body standing upright on the floor point `ground` (the waist above it at the rest
// pose's waist height), facing `forward` (made horizontal; unit), arms and legs straight down.
// forward parallel to up gives the identity rotation's heading projected (a defined pose).
ArticulatedPose UprightPose(const ArticulatedBody& body, const Eigen::Vector3d& ground,
                            const Eigen::Vector3d& up, const Eigen::Vector3d& forward);

// The body's forward (the pelvis's x axis) projected on the floor, unit; nullopt when it is
// (nearly) vertical.
std::optional<Eigen::Vector3d> HorizontalForward(const ArticulatedPose& pose,
                                                 const Eigen::Vector3d& up);

// The same pose turned about up by the angle from its horizontal forward to `forward` (about
// the waist joint), the limbs' local rotations kept.
ArticulatedPose TurnedTo(const ArticulatedPose& pose, const Eigen::Vector3d& up,
                         const Eigen::Vector3d& forward);

// The root's path over the last window frames (see the header comment).
class TravelDirection {
 public:
  // window >= 2 frames, min_distance_m > 0.
  TravelDirection(int window, double min_distance_m);

  // The root position of the next frame (sensor frame; a moving sensor's frames must be
  // world-consistent for the direction to mean anything: give world positions then).
  void Add(const Eigen::Vector3d& root);
  void Clear() { path_.clear(); }
  // The unit direction across the floor (up: unit), or nullopt while the root has not moved
  // min_distance_m within the window.
  std::optional<Eigen::Vector3d> Direction(const Eigen::Vector3d& up) const;

 private:
  int window_;
  double min_distance_m_;
  std::deque<Eigen::Vector3d> path_;
};

}  // namespace reenact::capture
