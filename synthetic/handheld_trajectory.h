#pragma once
// A hand-held sensor: an operator walks along a smooth path holding the sensor, aims it at a
// moving target (the subject), and adds the vertical bob of walking and a small hand shake.
// World frame: z up, floor z = 0, metres; poses are world_from_sensor of an OpenCV camera
// (x right, y down, z forward). Deterministic for a seed.
//
// Pose of frame k at time t = k / rate:
//   eye    = path[k] + bob(t) z + shake_t(t)
//   bob(t) = bob_amplitude_m * w(t) * sin(2 pi step_frequency_hz t), w = the operator's speed
//            over its largest speed along the path (no bob while standing)
//   shake_t(t)_i = shake_translation_m * (2 N(shake_frequency_hz t, i) - 1), i = x, y, z
//   world_from_sensor = LookAt(eye, target[k]) * Rx(a_x) Ry(a_y) Rz(a_z) (camera axes)
//   a_i = shake_rotation_deg * (2 N(shake_frequency_hz t, 3 + i) - 1)
// with N(x, i) the C1 value noise of procedural.h in [0, 1] along row i for the seed. So the
// shake stays within shake_translation_m per axis and shake_rotation_deg per axis, and the
// pose is C1 in time when path and target are.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <span>
#include <vector>

namespace reenact::capture {

struct HandheldOptions {
  double step_frequency_hz = 1.8;      // operator's steps, >= 0
  double bob_amplitude_m = 0.012;      // >= 0
  double shake_translation_m = 0.003;  // peak per axis, >= 0
  double shake_rotation_deg = 0.3;     // peak per axis, in [0, 5]
  double shake_frequency_hz = 3.0;     // noise lattice rate, > 0
  uint64_t seed = 1;

  // Throws CheckError when a field is out of range.
  void Check() const;
};

// world_from_sensor per frame. path and target have one point per frame (same length >= 1);
// the view direction target - eye must never be vertical. Throws CheckError otherwise.
std::vector<Eigen::Isometry3d> HandheldSensorPoses(std::span<const Eigen::Vector3d> path,
                                                   std::span<const Eigen::Vector3d> target,
                                                   double frame_rate_hz,
                                                   const HandheldOptions& options = {});

// The operator's smooth path for walk-handheld: an arc around `centre`, the azimuth easing
// from start_azimuth_deg to end_azimuth_deg (0: world -y of the centre, positive turning
// counter-clockwise seen from above) as (1 - cos(pi t / T)) / 2 (at rest at both ends), the
// radius radius_m + radius_wobble_m sin(2 pi t / radius_wobble_period_s), the height
// height_m + height_drift_m sin(2 pi t / height_drift_period_s). T = (frames - 1) / rate.
struct OperatorArcOptions {
  Eigen::Vector2d centre = Eigen::Vector2d(0.8, 0.0);
  double radius_m = 3.3;  // > radius_wobble_m >= 0
  double radius_wobble_m = 0.15;
  double radius_wobble_period_s = 4.5;  // > 0
  double start_azimuth_deg = -15;
  double end_azimuth_deg = -60;
  double height_m = 1.38;  // > height_drift_m >= 0
  double height_drift_m = 0.04;
  double height_drift_period_s = 6.0;  // > 0

  void Check() const;
};
std::vector<Eigen::Vector3d> OperatorArc(const OperatorArcOptions& options, int frames,
                                         double frame_rate_hz);

}  // namespace reenact::capture
