#pragma once
// Calibration of the tracker's body from one depth frame of the calibration pose (standing,
// facing the sensor, arms held out to the sides; the thesis's representative-frame criteria):
//  1. Body frame from the detected person (person_detector.h): up = the floor's normal,
//     forward = from the person towards the sensor across up, left = up x forward.
//  2. Standing height H = the person's top above the floor (head top). The pose test: the
//     lateral extent of the points between 0.6 H and 0.95 H above the floor (fingertip to
//     fingertip) is at least min_span_ratio H (a span is about H with arms out, 0.3 H with
//     arms down), and its middle lies within max_offset_ratio H of the legs' (the points
//     between 0.3 H and 0.5 H) median lateral position (both arms out, not one).
//  3. Shape: average adult proportions scaled to H (BodyShape::FromHeight), arm lengths
//     scaled to the span (span / 2 = shoulder half width + upper arm + forearm + the 0.062 H
//     from palm centre to fingertip), within [0.8, 1.25] of the proportional length.
//  4. Pose: arms out sideways, placed at the legs' lateral position, torso_radius behind the
//     torso's front surface; refined by the model fit (body_fit.h), then each capsule radius
//     re-estimated as the median distance to its axis of the points nearest to it (middle
//     70% of the axis), within [0.6, 1.5] of the proportional radius, and the trunk's half
//     breadth (fit_trunk_breadth) as the abdomen's silhouette half width facing the sensor
//     (torso_depth.h's MeasureTrunkBreadth), within [0.6, 1.5] of the proportional one, the
//     half depth kept; then fitted again (refine_rounds times).
//  5. Lengths (fit_lengths): the free lengths of shape_fit.h (hips, spine, shoulder drop,
//     legs, head; the arm chain stays at step 3's span estimate) fitted together with the
//     pose, the proportional shape of step 3 as their prior and the standing height as a
//     constraint (a subject's hips and legs are not at average fractions of its height);
//     then the radii and the pose once more. Bone lengths are then fixed for tracking.

#include <optional>
#include <string>
#include <string_view>

#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/body_fit.h"
#include "capture-client/tracker/person_detector.h"
#include "capture-client/tracker/shape_fit.h"
#include "common/model/cylinder_model.h"

namespace reenact::capture {

struct CalibrationOptions {
  double min_height_m = 1.0;  // plausible standing height, 0 < min < max
  double max_height_m = 2.3;
  double min_span_ratio = 0.75;    // arm span / height at least, > 0
  double max_offset_ratio = 0.08;  // span middle vs legs, / height, > 0
  int refine_rounds = 2;           // radius re-estimation rounds, >= 0
  // Step 4's trunk breadth, measured instead of the proportional one: the average proportions
  // can make a trunk several centimetres too broad (CesiumMan's 26 cm against its mesh's
  // 21-23 cm at the abdomen), and a trunk too broad takes a hanging arm's points
  // (torso_depth.h, MeasureTrunkBreadth).
  bool fit_trunk_breadth = true;
  BodyFitOptions fit{.iterations = 20};
  // Step 5: fit the segment lengths with the pose (shape_fit.h), then the radii and the pose
  // once more.
  bool fit_lengths = true;
  ShapeFitOptions shape;
  // ProportionalBody's head, where a neck depth was measured (head_size.h): the measured
  // ratio m = that depth over average_neck_depth_ratio H (what the measurement reads on a body
  // of average proportions: on the procedural body 0.097 H facing the sensor to 0.11-0.12 H
  // side-on) is shrunk towards 1 by head_scale_noise (the measurement's uncertainty: that
  // spread with the views, +-11 %, and a slice of 2-3 cm in a neck depth of 19 cm):
  // scale = 1 + sign(m - 1) max(0, |m - 1| - head_scale_noise), so a head within it of the
  // average keeps the average; then kept within [min_head_scale, max_head_scale].
  // ratio > 0, noise >= 0, 0 < min_head_scale <= 1 <= max_head_scale.
  double average_neck_depth_ratio = 0.108;
  double head_scale_noise = 0.15;
  double min_head_scale = 0.75;
  double max_head_scale = 1.7;

  void Check() const;
};

enum class CalibrationStatus {
  kOk = 0,
  kNoPerson,            // the blob is not a detected person
  kImplausibleHeight,   // H outside [min_height_m, max_height_m]
  kNotCalibrationPose,  // arms not held out to both sides
};
std::string_view CalibrationStatusName(CalibrationStatus status);

struct BodyCalibration {
  CalibrationStatus status = CalibrationStatus::kNoPerson;
  BodyShape shape;
  ArticulatedPose pose;  // the calibration frame's fitted pose
  BodyFitResult fit;     // of the final round
  double height_m = 0, span_m = 0;
  RadiusRatios radius_ratio{};  // radius / bone length of the 11 parts (cylinder_model.h)
  // false: the shape came from the height alone (ProportionalBody), without the pose.
  bool from_calibration_pose = true;
  // Tracked frames whose depth fitted the segment lengths on the fly (SkeletonTracker, for a
  // body started without the calibration pose); 0: none.
  int motion_frames = 0;
};

// Whether the blob shows the calibration pose, with its height and span (steps 1-2).
struct CalibrationPoseTest {
  CalibrationStatus status = CalibrationStatus::kNoPerson;
  double height_m = 0, span_m = 0;
  double centre_lateral_m = 0;  // legs' lateral position (left positive)
  Eigen::Matrix3d sensor_from_body = Eigen::Matrix3d::Identity();  // columns forward, left, up
  Eigen::Vector3d floor_origin = Eigen::Vector3d::Zero();          // floor point under the centroid
};
CalibrationPoseTest TestCalibrationPose(const PersonBlob& blob, const CalibrationOptions& options);

// The arms-out pose of `shape` at the blob (step 4's start), or nullopt when the blob does not
// show the calibration pose.
std::optional<ArticulatedPose> CalibrationStartPose(const ArticulatedBody& body,
                                                    const PersonBlob& blob,
                                                    const CalibrationPoseTest& test);

// The fallback for a subject who never shows the calibration pose: the shape from the
// standing height alone (step 3 without the span), status kOk when the height is plausible.
// neck_below_top_m: the head's neck depth measured in this and earlier frames (head_size.h;
// SkeletonTracker takes the median over the frames it waited for the calibration pose), which
// scales the head (WithHeadScaled, see CalibrationOptions); without it, an average head.
// The pose is left at its default; the caller places the body (SkeletonTracker does so as
// when recovering from the silhouette).
BodyCalibration ProportionalBody(const PersonBlob& blob, const CalibrationOptions& options = {},
                                 std::optional<double> neck_below_top_m = std::nullopt);

// `shape` with its head's radius and rise (neck -> head centre) times scale (> 0), the two
// spine lengths scaled together to keep the standing height: a larger head lowers the neck,
// the trunk and the hips, the legs stay.
BodyShape WithHeadScaled(const BodyShape& shape, double scale);

// `shape` with its thigh and shin times scale (> 0), the spine keeping the standing height as
// above: shorter legs lower the hips and lengthen the trunk.
BodyShape WithLegsScaled(const BodyShape& shape, double scale);

// A measured ratio m (> 0, finite) to the average, read as a scale: shrunk towards 1 by the
// measurement's noise (>= 0), 1 + sign(m - 1) max(0, |m - 1| - noise), so that a reading
// within the noise of the average keeps the average; then kept within [lo, hi].
double ScaleBeyondNoise(double m, double noise, double lo, double hi);

// Steps 1-4. subsample: data points every subsample-th grid point (>= 1).
BodyCalibration CalibrateBody(const PersonBlob& blob, const PinholeCamera& camera, int subsample,
                              const CalibrationOptions& options = {});

}  // namespace reenact::capture
