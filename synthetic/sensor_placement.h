#pragma once
// Where to put a static sensor so that a whole motion stays in view inside the synthetic room
// (room.h). World frame: z up, floor z = 0, metres.
//
// A sensor pose "sees" a skeleton when every joint, grown to a ball of body_radius_m, projects
// inside the image with margin_px to spare (|pixel - border| >= margin_px + f * r / depth),
// lies at least min_depth_m in front of the sensor, and the straight line from the sensor to
// the joint crosses no furniture box of the room.
//
// The search, first success wins:
// 1. The preferred pose: at `height_m`, preferred_distance_m in front of the subject's start
//    (the first frame's waist, along the way it faces: world -y, as the scenarios place it),
//    looking at that waist, as in turn-and-kick.
// 2. Otherwise the sensor looks at the centre of the motion (the middle of the horizontal
//    bounding box of all joints over all frames, at the mean waist height) from azimuth
//    theta = 0, +5, -5, +10, ... +-180 degrees (0: from world -y, positive turning
//    counter-clockwise seen from above) and, for each azimuth, the nearest distance from
//    min_distance_m up in steps of distance_step_m at which the sensor stands inside the
//    room (wall_clearance_m from every wall, outside the furniture) and sees every frame.
// So a walk that would leave the preferred view is watched from the front-most direction
// that holds all of it, as close as the room allows.

#include <Eigen/Geometry>
#include <span>
#include <vector>

#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"
#include "common/skeleton/skeleton.h"
#include "synthetic/room.h"

namespace reenact::capture {

struct StaticSensorOptions {
  double height_m = 1.3;              // sensor height above the floor, > 0
  double preferred_distance_m = 3.0;  // step 1, > 0
  double body_radius_m = 0.15;        // flesh around a joint, >= 0
  double margin_px = 8;               // >= 0
  double min_depth_m = 1.0;           // > 0
  double min_distance_m = 2.0;        // step 2 search range, 0 < min <= max
  double max_distance_m = 8.0;
  double distance_step_m = 0.1;   // > 0
  double wall_clearance_m = 0.3;  // >= 0

  // Throws CheckError when a field is out of range.
  void Check() const;
};

// True when the sensor at world_from_sensor sees the skeleton (every joint present is
// checked; see the header comment).
bool SensorSeesSkeleton(const Skeleton& skeleton, const PinholeCamera& camera,
                        const Eigen::Isometry3d& world_from_sensor, const RoomModel& room,
                        const StaticSensorOptions& options);

// world_from_sensor (OpenCV camera: x right, y down, z forward) of a static sensor that sees
// every skeleton of `motion`. Errors: "invalid_argument" for an empty motion or one whose
// first frame lacks the waist; "unsupported" when no position in the room sees the whole
// motion (the message gives the motion's extent).
Expected<Eigen::Isometry3d> PlaceStaticSensor(std::span<const Skeleton> motion,
                                              const PinholeCamera& camera, const RoomModel& room,
                                              const StaticSensorOptions& options = {});

}  // namespace reenact::capture
