#pragma once
// The body's heading when the subject has not shown the calibration pose: an upright
// person in any heading, seen in depth, where front and back give nearly the same silhouette
// and surface (most of all in a side view).
//  - Candidates: count headings evenly spaced about the floor's up, starting at "facing the
//    sensor"; each one an upright start pose (UprightPose) that the tracker fits, the fit
//    residual choosing among them.
//  - Travel: a walking subject faces the way it goes. TravelDirection keeps the root's path
//    and takes its direction across the floor over the last window_frames frames, or over as
//    many more (up to max_window_frames) as a slow walker needs to cover min_distance_m; none
//    while the root has not covered it. The walk must be steady: each half of the path (first
//    to middle position, middle to last) covers at least min_half_share of the distance. A
//    subject turning on the spot and then stepping back or aside does not face its
//    displacement (the CMU walk 131_01 does where it turns); a curved walk does, nearly
//    (walk-handheld's circle), so the path need not be straight. A slow walk covers 0.3 m in
//    50 frames rather than 20 (the CMU walk 131_02 on CesiumMan, 11 cm in 20 frames). The
//    tracker uses it to settle the front/back ambiguity: a fitted forward more than
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
// Whether the body faces away from a sensor at `sensor` (sensor frame: the origin): its
// horizontal forward points away from the horizontal direction to the sensor. False where
// either is (nearly) vertical or up is zero.
bool FacesAwayFrom(const ArticulatedPose& pose, const Eigen::Vector3d& up,
                   const Eigen::Vector3d& sensor);

ArticulatedPose UprightPose(const ArticulatedBody& body, const Eigen::Vector3d& ground,
                            const Eigen::Vector3d& up, const Eigen::Vector3d& forward);

// The body's forward (the pelvis's x axis) projected on the floor, unit; nullopt when it is
// (nearly) vertical.
std::optional<Eigen::Vector3d> HorizontalForward(const ArticulatedPose& pose,
                                                 const Eigen::Vector3d& up);

// The same pose turned about up by angle_rad (right-handed: counter-clockwise seen from above)
// about the waist joint, the limbs' local rotations kept; unchanged for a zero up.
ArticulatedPose TurnedBy(const ArticulatedPose& pose, const Eigen::Vector3d& up, double angle_rad);

// The same pose turned about up by the angle from its horizontal forward to `forward` (about
// the waist joint), the limbs' local rotations kept.
ArticulatedPose TurnedTo(const ArticulatedPose& pose, const Eigen::Vector3d& up,
                         const Eigen::Vector3d& forward);

struct TravelOptions {
  int window_frames = 20;        // >= 2
  int max_window_frames = 90;    // >= window_frames
  double min_distance_m = 0.3;   // > 0
  double min_half_share = 0.25;  // [0, 0.5]

  void Check() const;
};

// The root's path over the last frames (see the header comment).
class TravelDirection {
 public:
  explicit TravelDirection(const TravelOptions& options = {});

  // The root position of the next frame (sensor frame; a moving sensor's frames must be
  // world-consistent for the direction to mean anything: give world positions then).
  void Add(const Eigen::Vector3d& root);
  void Clear() { path_.clear(); }
  // The unit direction across the floor (up: unit), or nullopt while the root has not covered
  // min_distance_m in a steady walk.
  std::optional<Eigen::Vector3d> Direction(const Eigen::Vector3d& up) const;

 private:
  TravelOptions options_;
  std::deque<Eigen::Vector3d> path_;
};

}  // namespace reenact::capture
