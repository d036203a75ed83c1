#pragma once
// Scripted motions of the synthetic subject and the sensor's pose per frame.
//
// "turn-and-kick" (30 fps, 180 frames = 6 s):
//   0.0-0.7 s  calibration pose: facing the sensor, arms held out to the sides
//   0.7-1.2 s  arms come down to the sides
//   1.2-4.0 s  a full 360-degree turn in place (to the subject's left), stepping, with
//              swinging arms
//   4.0-5.0 s  a front kick with the right leg, arms in guard
//   5.0-6.0 s  the right arm raised overhead, the left arm out sideways, then lowered
// "raise-and-crouch" (30 fps, 180 frames = 6 s):
//   0.0-0.7 s  calibration pose;  0.7-1.2 s  arms come down to the sides
//   1.2-1.9 s  both arms raised forward to horizontal;  1.9-2.6 s  on to overhead (168
//              degrees), held to 2.9 s;  2.9-3.4 s  back to forward, held through the squat
//   3.3-4.4 s  down into a deep squat (hips flexed 105 degrees, knees bent 135, the trunk
//              leaning 50 degrees forward, so the centre of mass stays over the feet; the
//              waist drops from 1.00 m to 0.40 m), held to 4.8 s;  4.8-5.6 s  rising
//   5.2-5.9 s  arms down to the sides.
//   The feet stay planted and flat: each ankle dorsiflexes by its shin's forward tilt and
//   rolls against the leg's abduction (sole level), the abduction grows as the legs bend so
//   that the ankles keep their sideways offset, and the waist moves back (root_xy) so that
//   the ankles keep their place on the floor (PoseBody keeps them at their height).
// "calibration" (30 fps, 30 frames): the calibration pose held still.
// "model-walk" (30 fps, 120 frames = 4 s): the skinned model's own animation (its first,
//   looping; CesiumMan's is a 2 s walk in place), for a skinned body only; the subject at
//   the origin facing world -y.
// All four with a static sensor about 3 m in front of the subject at 1.3 m height, looking
// at it.
//
// "upper-body-turn" (30 fps, 195 frames = 6.5 s): a close-up without the calibration pose.
//   The subject stands at world (0, 1) (the waist), first facing world -y, arms relaxed at
//   the sides with the elbows a little bent.
//   0.3-1.7 s  the right hand raised in front of the shoulder and waved side to side
//              (0.7-1.3 s)
//   1.7-5.3 s  a full 360-degree turn in place (to the subject's left), stepping, with
//              swinging arms (as turn-and-kick's turn)
//   5.3-6.5 s  both forearms brought up forward (hands in front of the waist), held
//              5.8-6.1 s, and lowered
//   Static sensor 0.91 m in front of the body's vertical axis (its chest's surface about
//   0.8 m away when facing it) at 1.25 m height, looking level along world +y. On the
//   procedural body (1.75 m) the image shows the head (the top of the skull cut off) and the
//   trunk to the hips, on CesiumMan (1.51 m) the head and the trunk to the torso joint; the
//   knees and feet are out of view on every frame, and so is the floor: the image's lowest
//   ray (23.5 degrees down) meets the back wall, 2.41 m ahead, 0.2 m above the floor. The
//   subject's nearest point stays 0.5 m or more away (beyond a Kinect's 0.4 m minimum).
//
// "walk-handheld" (30 fps, 225 frames = 7.5 s): 0-0.7 s the calibration pose facing the
//   sensor, 0.7-1.2 s arms down, then one full circle of 0.8 m radius walked in 6.3 s
//   (walk_motion.h: from the origin, first facing world -y, turning to its left, smooth
//   start and stop, top speed 0.91 m/s), seen by a hand-held sensor (handheld_trajectory.h):
//   an operator walking an arc 3.15-3.45 m from the circle's centre (0.8, 0), from 15 to 60
//   degrees clockwise of the centre's world -y side, sensor at 1.34-1.42 m plus walking bob
//   (1.2 cm), aimed at the subject's path point at 0.9 m height, with hand shake of at most
//   3 mm and 0.3 degrees per axis drawn from the seed.
//
// "bvh:PATH" (30 fps): real motion capture from a BVH file (bvh_motion.h: resampled, placed
//   at the origin facing world -y, feet on the floor) as target_skeletons, played on either
//   body by bone directions. Static sensor (sensor_placement.h): 3 m in front of the start at
//   1.3 m when the whole motion stays in view from there; otherwise the front-most direction
//   around the motion's centre, as close as the room allows, from which every frame stays in
//   view (placed for the motion's own skeletons, not the body's).

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/error/expected.h"
#include "common/skeleton/skeleton.h"
#include "synthetic/body_model.h"

namespace reenact::capture {

struct Scenario {
  std::string name;
  double frame_rate_hz = 30;
  // The motion, exactly one of:
  std::vector<BodyPose> poses;             // procedural motion (any body), one per frame
  std::vector<Skeleton> target_skeletons;  // motion given as joint positions (bvh:), world
                                           // frame z-up metres, one per frame; played on
                                           // either body by bone directions
  bool model_animation = false;            // the skinned model's own animation
  int model_animation_frames = 0;          //   (frames to play when model_animation)
  // The sensor pose per frame (a static sensor: all equal). Same length as the motion.
  std::vector<Eigen::Isometry3d> world_from_sensor;

  // Frames of the motion: poses.size(), target_skeletons.size() or model_animation_frames.
  int frame_count() const;
};

// The scenario names; the last, "bvh:FILE", stands for "bvh:" followed by a path.
std::vector<std::string> SyntheticScenarioNames();

// The named scenario; seed drives the hand shake of walk-handheld (other scenarios do not
// depend on it). Errors: "not_found" listing the known names for an unknown name; for
// "bvh:PATH" the errors of LoadBvhMotion and PlaceStaticSensor, prefixed with the scenario
// name (so they name the path and the problem).
Expected<Scenario> MakeScenario(std::string_view name, uint64_t seed = 1);

// world_from_camera of an OpenCV camera at `eye` looking at `target`, image up along world
// +z (eye and target in the world frame; the view direction must not be vertical).
Eigen::Isometry3d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target);

}  // namespace reenact::capture
