#pragma once
// The tracker's capsule body (articulated_body.h) seen by a level sensor, for the tracker's
// tests: every pixel's ray is intersected with the posed body's capsules (the nearest hit
// kept), giving the visible surface points in the sensor frame, as a depth region of a person
// would. The sensor stands 1.3 m above the floor (the plane y = 1.3, OpenCV axes).

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "capture-client/segment/floor_plane.h"
#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/body_fit.h"
#include "capture-client/tracker/heading.h"
#include "capture-client/tracker/person_detector.h"

namespace reenact::capture::tracker_test {

// Rotations about the camera axes, radians.
inline Eigen::Matrix3d Rx(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).matrix();
}
inline Eigen::Matrix3d Ry(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).matrix();
}
inline Eigen::Matrix3d Rz(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).matrix();
}

inline constexpr double kSensorHeight = 1.3;

// The floor under the level sensor, normal up (-y).
inline Plane3 LevelFloor() { return Plane3{Eigen::Vector3d(0, -1, 0), -kSensorHeight}; }

// The body standing at depth z facing the sensor, arms down (UprightPose).
inline ArticulatedPose FacingSensor(const ArticulatedBody& body, double z = 3.0) {
  return UprightPose(body, Eigen::Vector3d(0, kSensorHeight, z), Eigen::Vector3d(0, -1, 0),
                     Eigen::Vector3d(0, 0, -1));
}

// Nearest positive ray parameter t of the ray t * d (d unit, from the origin) into the capsule
// a-b of radius r; infinity when it misses.
inline double RayCapsule(const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, double r) {
  double best = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& c : {a, b}) {  // end spheres: |t d - c|^2 = r^2
    const double dc = d.dot(c), disc = dc * dc - (c.squaredNorm() - r * r);
    if (disc >= 0 && dc - std::sqrt(disc) > 0) best = std::min(best, dc - std::sqrt(disc));
  }
  const Eigen::Vector3d axis = b - a;
  const double len = axis.norm();
  if (len < 1e-12) return best;
  const Eigen::Vector3d w = axis / len;
  // Side: |(t d - a) - ((t d - a).w) w|^2 = r^2, with the foot of the hit within [0, len].
  const Eigen::Vector3d dp = d - d.dot(w) * w, ap = -a - (-a).dot(w) * w;
  const double qa = dp.squaredNorm(), qb = 2 * dp.dot(ap), qc = ap.squaredNorm() - r * r;
  const double disc = qb * qb - 4 * qa * qc;
  if (qa > 1e-12 && disc >= 0) {
    const double t = (-qb - std::sqrt(disc)) / (2 * qa);
    const double s = (t * d - a).dot(w);
    if (t > 0 && s >= 0 && s <= len) best = std::min(best, t);
  }
  return best;
}

// The visible surface points of the posed body, one per pixel of a width x height image with
// focal length f (pixels) and the principal point at the centre.
inline std::vector<Eigen::Vector3d> RenderBodyPoints(const ArticulatedBody& body,
                                                     const ArticulatedPose& pose, int width = 320,
                                                     int height = 240, double f = 285) {
  const PosedBody3 posed = body.Pose(pose);
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> axes;
  std::vector<double> radii;
  for (const BodyCapsule& c : body.capsules()) {
    const Eigen::Isometry3d& t = posed.sensor_from_segment[static_cast<int>(c.segment)];
    axes.emplace_back(t * c.a, t * c.b);
    radii.push_back(c.radius);
  }
  std::vector<Eigen::Vector3d> points;
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      const Eigen::Vector3d d =
          Eigen::Vector3d((u - 0.5 * width) / f, (v - 0.5 * height) / f, 1).normalized();
      double t = std::numeric_limits<double>::infinity();
      for (size_t k = 0; k < axes.size(); ++k)
        t = std::min(t, RayCapsule(d, axes[k].first, axes[k].second, radii[k]));
      if (std::isfinite(t)) points.push_back(t * d);
    }
  return points;
}

// A fit's observation of `points` alone: the silhouette and depth images of a Kinect-like grid
// left empty (fit with silhouette_weight 0).
inline BodyObservation PointsObservation(std::vector<Eigen::Vector3d> points) {
  BodyObservation obs;
  obs.camera = PinholeCamera::KinectLike();
  obs.grid_step_px = 2;
  const int w = obs.camera.width / 2, h = obs.camera.height / 2;
  obs.silhouette = ImageGray8(w, h, 1, 0);
  obs.depth_m = Image<float>(w, h, 1, 0.f);
  obs.outside_px = Image<float>(w, h, 1, 0.f);
  obs.points = std::move(points);
  return obs;
}

// A capsule of a ray-cast figure (SceneBlob), sensor frame, metres.
struct SceneCapsule {
  Eigen::Vector3d a, b;
  double radius;
};

// A point `height` above the floor under the level sensor, at (x, z) of the sensor frame.
inline Eigen::Vector3d AboveFloor(double x, double height, double z) {
  return Eigen::Vector3d(x, kSensorHeight - height, z);
}

// A figure's person blob as the detector gives it: every 2nd pixel of the Kinect-like camera
// that sees one of the capsules (mask, depth readings as z, points and their grid pixels),
// status kOk, the level floor known.
inline PersonBlob SceneBlob(const std::vector<SceneCapsule>& figure) {
  const PinholeCamera cam = PinholeCamera::KinectLike();
  PersonBlob blob;
  blob.status = DetectStatus::kOk;
  blob.grid_step_px = 2;
  blob.floor_in_sensor = LevelFloor();
  blob.mask = ImageGray8(cam.width / 2, cam.height / 2, 1, 0);
  blob.depth_m = Image<float>(cam.width / 2, cam.height / 2, 1, 0.f);
  for (int v = 0; v < cam.height; v += 2)
    for (int u = 0; u < cam.width; u += 2) {
      const Eigen::Vector3d d =
          Eigen::Vector3d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1).normalized();
      double t = std::numeric_limits<double>::infinity();
      for (const SceneCapsule& c : figure) t = std::min(t, RayCapsule(d, c.a, c.b, c.radius));
      if (!std::isfinite(t)) continue;
      const Eigen::Vector3d p = t * d;
      blob.mask.at(u / 2, v / 2) = 255;
      blob.depth_m.at(u / 2, v / 2) = static_cast<float>(p.z());
      blob.points.push_back(p);
      blob.pixels.emplace_back(u / 2, v / 2);
    }
  return blob;
}

}  // namespace reenact::capture::tracker_test
