#pragma once
// The body measured while it is tracked, on good frames:
//  - The trunk's depth from side views (torso_depth.h), for a body calibrated from the
//    calibration pose (whose front view shows the breadth but not the depth): once
//    torso_depth.side_frames frames have seen the trunk within torso_depth.max_side_deg of
//    side-on, the trunk's capsules take the measured depth, their breadth kept; then fixed.
//    Not for a start without the calibration pose, which has no measured breadth: on
//    CesiumMan's CMU walks the deeper trunk left more frames facing backwards for no gain.
//  - A body started without the calibration pose (average proportions): once at least
//    min_crotch_frames frames have measured the crotch's height (crotch_height.h), the legs
//    are scaled by it: the 90th percentile c of the heights (the crotch itself; lower readings
//    come from lines up an inner thigh) against average_crotch_ratio H (what it reads on the
//    procedural body walking) moves the hips by c - average_crotch_ratio H, so the legs scale
//    by m = 1 + that / (thigh + shin), shrunk towards 1 by leg_scale_noise and kept within
//    [min_leg_scale, max_leg_scale] (ScaleBeyondNoise), the spine keeping the height. Then
//    the segment lengths of shape_fit.h are fitted over motion_frames frames at least
//    motion_frame_spacing apart, each with the thighs at least motion_min_leg_spread_rad
//    apart (legs apart show the hips and leg lengths that a straight stance hides); then
//    fixed.

#include <optional>
#include <vector>

#include "capture-client/tracker/body_calibration.h"
#include "capture-client/tracker/body_fitter.h"
#include "capture-client/tracker/crotch_height.h"
#include "capture-client/tracker/torso_depth.h"

namespace reenact::capture {

struct BodyMeasurementOptions {
  bool measure_torso_depth = true;
  TorsoDepthOptions torso_depth;
  int motion_frames = 4;                   // >= 0; 0: the lengths are not fitted on the fly
  int motion_frame_spacing = 4;            // >= 1
  double motion_min_leg_spread_rad = 0.3;  // >= 0
  CrotchHeightOptions crotch;
  int min_crotch_frames = 5;            // >= 1
  double average_crotch_ratio = 0.478;  // > 0
  double leg_scale_noise = 0.05;        // >= 0
  double min_leg_scale = 0.8;           // (0, 1]
  double max_leg_scale = 1.2;           // >= 1

  void Check() const;
};

// The tracked body and its calibration, which a measurement changes.
struct MeasuredBody {
  BodyCalibration& calibration;
  std::optional<ArticulatedBody>& body;
  ArticulatedPose& pose;  // the track's pose (refitted with the lengths)
};

class BodyMeasurement {
 public:
  BodyMeasurement(const BodyMeasurementOptions& options, const CalibrationOptions& calibration);

  // A good tracked frame's fit, on the body as it was fitted.
  void Add(const BodyFitResult& fit, const BodyObservation& obs, const PersonBlob& blob,
           const PinholeCamera& camera, const BodyFitterOptions& fitter, MeasuredBody body);
  void Clear();

 private:
  bool LengthsPending(const BodyCalibration& calibration) const;
  void AddMotionFrame(const BodyFitResult& fit, const BodyObservation& obs,
                      const BodyFitterOptions& fitter, MeasuredBody body);
  // The legs scaled by the crotch heights collected, where there are enough.
  void ScaleLegs(MeasuredBody body) const;
  void AddCrotchHeight(const BodyFitResult& fit, const PersonBlob& blob,
                       const PinholeCamera& camera, const BodyCalibration& calibration);
  void AddTorsoWidths(const BodyFitResult& fit, const PersonBlob& blob, const PinholeCamera& camera,
                      MeasuredBody body);

  BodyMeasurementOptions options_;
  CalibrationOptions calibration_;
  std::vector<BodyObservation> motion_obs_;
  std::vector<ArticulatedPose> motion_poses_;
  int since_motion_frame_ = 0;
  std::vector<double> crotch_heights_;
  TorsoDepthCollector torso_depth_;
};

// Replaces the body's shape in the body and the calibration (its radius ratios too).
void AdoptShape(const BodyShape& shape, MeasuredBody body);

}  // namespace reenact::capture
