#include "capture-client/tracker/body_measurement.h"

#include <algorithm>
#include <cmath>

#include "common/error/check.h"

namespace reenact::capture {

void BodyMeasurementOptions::Check() const {
  torso_depth.Check();
  crotch.Check();
  REENACT_CHECK(motion_frames >= 0 && motion_frame_spacing >= 1 && motion_min_leg_spread_rad >= 0,
                "motion_frames >= 0, motion_frame_spacing >= 1, motion_min_leg_spread_rad >= 0");
  REENACT_CHECK(min_crotch_frames >= 1 && average_crotch_ratio > 0 && leg_scale_noise >= 0 &&
                    min_leg_scale > 0 && min_leg_scale <= 1 && max_leg_scale >= 1,
                "need min_crotch_frames >= 1, average_crotch_ratio > 0, leg_scale_noise >= 0 "
                "and 0 < min_leg_scale <= 1 <= max_leg_scale");
}

void AdoptShape(const BodyShape& shape, MeasuredBody body) {
  body.body.emplace(shape);
  body.calibration.shape = shape;
  const auto lengths = shape.PartLengths();
  const auto radii = shape.PartRadii();
  for (int i = 0; i < kBodyPartCount; ++i) body.calibration.radius_ratio[i] = radii[i] / lengths[i];
}

BodyMeasurement::BodyMeasurement(const BodyMeasurementOptions& options,
                                 const CalibrationOptions& calibration)
    : options_(options), calibration_(calibration), torso_depth_(options.torso_depth) {
  options.Check();
}

void BodyMeasurement::Clear() {
  motion_obs_.clear();
  motion_poses_.clear();
  since_motion_frame_ = 0;
  crotch_heights_.clear();
  torso_depth_.Clear();
}

bool BodyMeasurement::LengthsPending(const BodyCalibration& calibration) const {
  return !calibration.from_calibration_pose && calibration.motion_frames == 0 &&
         options_.motion_frames > 0;
}

void BodyMeasurement::Add(const BodyFitResult& fit, const BodyObservation& obs,
                          const PersonBlob& blob, const PinholeCamera& camera,
                          const BodyFitterOptions& fitter, MeasuredBody body) {
  AddMotionFrame(fit, obs, fitter, body);
  AddCrotchHeight(fit, blob, camera, body.calibration);
  AddTorsoWidths(fit, blob, camera, body);
}

void BodyMeasurement::AddMotionFrame(const BodyFitResult& fit, const BodyObservation& obs,
                                     const BodyFitterOptions& fitter, MeasuredBody body) {
  if (!LengthsPending(body.calibration)) return;
  ++since_motion_frame_;
  if (!motion_obs_.empty() && since_motion_frame_ < options_.motion_frame_spacing) return;
  const auto& seg = fit.posed.sensor_from_segment;
  const Eigen::Vector3d l = seg[static_cast<int>(BodySegment::kLeftThigh)].linear().col(2);
  const Eigen::Vector3d r = seg[static_cast<int>(BodySegment::kRightThigh)].linear().col(2);
  if (std::acos(std::clamp(l.dot(r), -1.0, 1.0)) < options_.motion_min_leg_spread_rad) return;
  motion_obs_.push_back(obs);
  motion_poses_.push_back(fit.pose);
  since_motion_frame_ = 0;
  if (static_cast<int>(motion_obs_.size()) < options_.motion_frames) return;
  std::vector<const BodyObservation*> observations;
  for (const BodyObservation& o : motion_obs_) observations.push_back(&o);
  ScaleLegs(body);
  const MultiFrameShapeFit sf =
      FitBodyShapeFrames(body.body->shape(), motion_poses_, observations, body.calibration.height_m,
                         fitter.fit, calibration_.shape, fitter.limits);
  AdoptShape(sf.shape, body);
  body.calibration.motion_frames = static_cast<int>(motion_obs_.size());
  body.pose = sf.poses.back();
  motion_obs_.clear();
  motion_poses_.clear();
  crotch_heights_.clear();
}

void BodyMeasurement::ScaleLegs(MeasuredBody body) const {
  if (static_cast<int>(crotch_heights_.size()) < options_.min_crotch_frames) return;
  std::vector<double> h = crotch_heights_;
  const size_t k = std::min(h.size() - 1, static_cast<size_t>(0.9 * h.size()));
  std::nth_element(h.begin(), h.begin() + k, h.end());
  const BodyShape& shape = body.body->shape();
  const double m = 1 + (h[k] - options_.average_crotch_ratio * body.calibration.height_m) /
                           (shape.thigh + shape.shin);
  if (m > 0)
    body.body.emplace(
        WithLegsScaled(shape, ScaleBeyondNoise(m, options_.leg_scale_noise, options_.min_leg_scale,
                                               options_.max_leg_scale)));
}

void BodyMeasurement::AddCrotchHeight(const BodyFitResult& fit, const PersonBlob& blob,
                                      const PinholeCamera& camera,
                                      const BodyCalibration& calibration) {
  if (!LengthsPending(calibration)) return;
  const auto& joints = fit.posed.skeleton.position;
  const auto c = MeasureCrotchHeight(blob, camera, joints[static_cast<int>(Joint::kLeftFoot)],
                                     joints[static_cast<int>(Joint::kRightFoot)], options_.crotch);
  if (c) crotch_heights_.push_back(*c);
}

void BodyMeasurement::AddTorsoWidths(const BodyFitResult& fit, const PersonBlob& blob,
                                     const PinholeCamera& camera, MeasuredBody body) {
  if (!options_.measure_torso_depth || torso_depth_.done() ||
      !body.calibration.from_calibration_pose)
    return;
  const std::optional<double> half_depth = torso_depth_.Add(
      MeasureTrunkWidths(*body.body, fit.posed, blob, camera, options_.torso_depth));
  if (half_depth)
    AdoptShape(
        WithTorsoDepth(body.body->shape(), *half_depth, options_.torso_depth.min_depth_ratio),
        body);
}

}  // namespace reenact::capture
