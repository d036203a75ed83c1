#include "synthetic/sensor_placement.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "common/error/check.h"
#include "synthetic/scenario.h"

namespace reenact::capture {
namespace {

// Whether the segment a-b meets the box (slab test).
bool SegmentHitsBox(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Box& box) {
  double t0 = 0, t1 = 1;
  const Eigen::Vector3d d = b - a;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (a[k] < box.min[k] || a[k] > box.max[k]) return false;
      continue;
    }
    double u = (box.min[k] - a[k]) / d[k], v = (box.max[k] - a[k]) / d[k];
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u);
    t1 = std::min(t1, v);
    if (t0 > t1) return false;
  }
  return true;
}

bool InsideBox(const Eigen::Vector3d& p, const Box& box, double grow) {
  return (p.array() >= box.min.array() - grow).all() && (p.array() <= box.max.array() + grow).all();
}

bool InsideWalls(const Eigen::Vector3d& eye, const RoomModel& room, double clearance) {
  for (int k = 0; k < 3; ++k)
    if (eye[k] < room.room_min[k] + clearance || eye[k] > room.room_max[k] - clearance)
      return false;
  return true;
}

bool InFurniture(const Eigen::Vector3d& eye, const RoomModel& room, double clearance) {
  for (const Box& box : room.furniture)
    if (InsideBox(eye, box, clearance)) return true;
  return false;
}

bool SeesAll(std::span<const Skeleton> motion, const PinholeCamera& camera,
             const Eigen::Isometry3d& world_from_sensor, const RoomModel& room,
             const StaticSensorOptions& options) {
  for (const Skeleton& s : motion)
    if (!SensorSeesSkeleton(s, camera, world_from_sensor, room, options)) return false;
  return true;
}

}  // namespace

void StaticSensorOptions::Check() const {
  auto finite = [](double v) { return std::isfinite(v); };
  REENACT_CHECK(finite(height_m) && height_m > 0, "height_m must be > 0");
  REENACT_CHECK(finite(preferred_distance_m) && preferred_distance_m > 0,
                "preferred_distance_m must be > 0");
  REENACT_CHECK(finite(body_radius_m) && body_radius_m >= 0, "body_radius_m must be >= 0");
  REENACT_CHECK(finite(margin_px) && margin_px >= 0, "margin_px must be >= 0");
  REENACT_CHECK(finite(min_depth_m) && min_depth_m > 0, "min_depth_m must be > 0");
  REENACT_CHECK(finite(min_distance_m) && finite(max_distance_m) && min_distance_m > 0 &&
                    min_distance_m <= max_distance_m,
                "need 0 < min_distance_m <= max_distance_m");
  REENACT_CHECK(finite(distance_step_m) && distance_step_m > 0, "distance_step_m must be > 0");
  REENACT_CHECK(finite(wall_clearance_m) && wall_clearance_m >= 0, "wall_clearance_m must be >= 0");
}

bool SensorSeesSkeleton(const Skeleton& skeleton, const PinholeCamera& camera,
                        const Eigen::Isometry3d& world_from_sensor, const RoomModel& room,
                        const StaticSensorOptions& options) {
  const Eigen::Isometry3d sensor_from_world = world_from_sensor.inverse();
  const Eigen::Vector3d eye = world_from_sensor.translation();
  for (int j = 0; j < kJointCount; ++j) {
    if (!skeleton.Has(static_cast<Joint>(j))) continue;
    const Eigen::Vector3d p = sensor_from_world * skeleton.position[j];
    if (!(p.z() >= options.min_depth_m)) return false;
    const std::optional<Eigen::Vector2d> px = camera.Project(p);
    if (!px) return false;
    const double rx = options.margin_px + camera.fx * options.body_radius_m / p.z();
    const double ry = options.margin_px + camera.fy * options.body_radius_m / p.z();
    if (px->x() < rx || px->x() > camera.width - rx || px->y() < ry || px->y() > camera.height - ry)
      return false;
    for (const Box& box : room.furniture)
      if (SegmentHitsBox(eye, skeleton.position[j], box)) return false;
  }
  return true;
}

Expected<Eigen::Isometry3d> PlaceStaticSensor(std::span<const Skeleton> motion,
                                              const PinholeCamera& camera, const RoomModel& room,
                                              const StaticSensorOptions& options) {
  options.Check();
  if (motion.empty()) return MakeError("invalid_argument", "no frames to place a sensor for");
  if (!motion.front().Has(Joint::kWaist))
    return MakeError("invalid_argument", "the first frame has no waist joint");

  // 1. In front of the start.
  const Eigen::Vector3d start = motion.front()[Joint::kWaist];
  const Eigen::Vector3d preferred_eye(start.x(), start.y() - options.preferred_distance_m,
                                      options.height_m);
  const Eigen::Isometry3d preferred = LookAt(preferred_eye, start);
  if (InsideWalls(preferred_eye, room, options.wall_clearance_m) &&
      !InFurniture(preferred_eye, room, options.wall_clearance_m) &&
      SeesAll(motion, camera, preferred, room, options))
    return preferred;

  // 2. Around the motion's centre.
  Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  double waist_z = 0;
  int waists = 0;
  for (const Skeleton& s : motion) {
    for (int j = 0; j < kJointCount; ++j) {
      if (!s.Has(static_cast<Joint>(j))) continue;
      lo = lo.cwiseMin(s.position[j].head<2>());
      hi = hi.cwiseMax(s.position[j].head<2>());
    }
    if (s.Has(Joint::kWaist)) waist_z += s[Joint::kWaist].z(), ++waists;
  }
  const Eigen::Vector2d centre_xy = (lo + hi) / 2;
  const Eigen::Vector3d centre(centre_xy.x(), centre_xy.y(), waist_z / waists);
  for (int step = 0; step <= 72; ++step) {
    const double theta_deg = (step % 2 == 1 ? 1 : -1) * 5.0 * ((step + 1) / 2);
    const double theta = theta_deg * std::numbers::pi / 180;
    const Eigen::Vector2d toward(std::sin(theta), -std::cos(theta));  // theta 0: world -y
    for (double d = options.min_distance_m; d <= options.max_distance_m + 1e-9;
         d += options.distance_step_m) {
      const Eigen::Vector2d xy = centre_xy + d * toward;
      const Eigen::Vector3d eye(xy.x(), xy.y(), options.height_m);
      // Walls are convex: beyond the first position outside them, all are outside.
      if (!InsideWalls(eye, room, options.wall_clearance_m)) break;
      if (InFurniture(eye, room, options.wall_clearance_m)) continue;
      const Eigen::Isometry3d pose = LookAt(eye, centre);
      if (SeesAll(motion, camera, pose, room, options)) return pose;
    }
  }
  char extent[160];
  std::snprintf(extent, sizeof extent, "x [%.2f, %.2f] m, y [%.2f, %.2f] m", lo.x(), hi.x(), lo.y(),
                hi.y());
  return MakeError("unsupported", std::string("no static sensor position inside the room (") +
                                      "or within its search range) keeps the whole motion in "
                                      "view; the motion spans " +
                                      extent);
}

}  // namespace reenact::capture
