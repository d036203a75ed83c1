#include "synthetic/handheld_trajectory.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/error/check.h"
#include "synthetic/procedural.h"
#include "synthetic/scenario.h"

namespace reenact::capture {
namespace {

constexpr double kPi = std::numbers::pi;

// Value noise along row `row`, mapped to [-1, 1].
double Noise(double x, int row, uint64_t seed) { return 2 * ValueNoise(x, 7.0 * row, seed) - 1; }

}  // namespace

void HandheldOptions::Check() const {
  auto ok = [](double v) { return std::isfinite(v) && v >= 0; };
  REENACT_CHECK(ok(step_frequency_hz), "step_frequency_hz must be >= 0");
  REENACT_CHECK(ok(bob_amplitude_m), "bob_amplitude_m must be >= 0");
  REENACT_CHECK(ok(shake_translation_m), "shake_translation_m must be >= 0");
  REENACT_CHECK(ok(shake_rotation_deg) && shake_rotation_deg <= 5,
                "shake_rotation_deg must be in [0, 5]");
  REENACT_CHECK(std::isfinite(shake_frequency_hz) && shake_frequency_hz > 0,
                "shake_frequency_hz must be > 0");
}

void OperatorArcOptions::Check() const {
  REENACT_CHECK(centre.allFinite(), "centre must be finite");
  REENACT_CHECK(std::isfinite(radius_m) && std::isfinite(radius_wobble_m) && radius_wobble_m >= 0 &&
                    radius_m > radius_wobble_m,
                "need radius_m > radius_wobble_m >= 0");
  REENACT_CHECK(std::isfinite(height_m) && std::isfinite(height_drift_m) && height_drift_m >= 0 &&
                    height_m > height_drift_m,
                "need height_m > height_drift_m >= 0");
  REENACT_CHECK(std::isfinite(radius_wobble_period_s) && radius_wobble_period_s > 0 &&
                    std::isfinite(height_drift_period_s) && height_drift_period_s > 0,
                "periods must be > 0");
  REENACT_CHECK(std::isfinite(start_azimuth_deg) && std::isfinite(end_azimuth_deg),
                "azimuths must be finite");
}

std::vector<Eigen::Isometry3d> HandheldSensorPoses(std::span<const Eigen::Vector3d> path,
                                                   std::span<const Eigen::Vector3d> target,
                                                   double frame_rate_hz, const HandheldOptions& o) {
  o.Check();
  REENACT_CHECK(!path.empty() && path.size() == target.size(),
                "path and target need one point per frame, at least one");
  REENACT_CHECK(std::isfinite(frame_rate_hz) && frame_rate_hz > 0, "frame_rate_hz must be > 0");
  const size_t n = path.size();
  // The operator's speed per frame (central differences) and its largest value.
  std::vector<double> speed(n, 0.0);
  for (size_t k = 0; k < n; ++k) {
    const size_t a = k == 0 ? 0 : k - 1, b = std::min(n - 1, k + 1);
    if (b > a) speed[k] = (path[b] - path[a]).norm() * frame_rate_hz / static_cast<double>(b - a);
  }
  const double top = *std::max_element(speed.begin(), speed.end());

  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(n);
  const double deg = kPi / 180;
  for (size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / frame_rate_hz;
    const double x = o.shake_frequency_hz * t;
    const double walking = top > 0 ? speed[k] / top : 0.0;
    Eigen::Vector3d eye = path[k];
    eye.z() += o.bob_amplitude_m * walking * std::sin(2 * kPi * o.step_frequency_hz * t);
    for (int i = 0; i < 3; ++i) eye[i] += o.shake_translation_m * Noise(x, i, o.seed);
    const Eigen::Matrix3d shake =
        (Eigen::AngleAxisd(o.shake_rotation_deg * deg * Noise(x, 3, o.seed),
                           Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(o.shake_rotation_deg * deg * Noise(x, 4, o.seed),
                           Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(o.shake_rotation_deg * deg * Noise(x, 5, o.seed),
                           Eigen::Vector3d::UnitZ()))
            .toRotationMatrix();
    Eigen::Isometry3d pose = LookAt(eye, target[k]);
    pose.linear() = pose.linear() * shake;
    poses.push_back(pose);
  }
  return poses;
}

std::vector<Eigen::Vector3d> OperatorArc(const OperatorArcOptions& o, int frames,
                                         double frame_rate_hz) {
  o.Check();
  REENACT_CHECK(frames >= 1, "frames must be >= 1");
  REENACT_CHECK(std::isfinite(frame_rate_hz) && frame_rate_hz > 0, "frame_rate_hz must be > 0");
  const double duration = (frames - 1) / frame_rate_hz;
  std::vector<Eigen::Vector3d> path;
  path.reserve(frames);
  for (int k = 0; k < frames; ++k) {
    const double t = k / frame_rate_hz;
    const double ease = duration > 0 ? (1 - std::cos(kPi * t / duration)) / 2 : 0.0;
    const double azimuth =
        (o.start_azimuth_deg + (o.end_azimuth_deg - o.start_azimuth_deg) * ease) * kPi / 180;
    const double radius =
        o.radius_m + o.radius_wobble_m * std::sin(2 * kPi * t / o.radius_wobble_period_s);
    const double height =
        o.height_m + o.height_drift_m * std::sin(2 * kPi * t / o.height_drift_period_s);
    path.emplace_back(o.centre.x() + radius * std::sin(azimuth),
                      o.centre.y() - radius * std::cos(azimuth), height);
  }
  return path;
}

}  // namespace reenact::capture
