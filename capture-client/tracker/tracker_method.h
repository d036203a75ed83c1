#pragma once
// The depth tracker's method: each module's parameters and the ordered list of correction
// steps (correction_step.h). DefaultTrackerMethod builds the product's from its options; an
// experiment (tests/eval/) builds its own to measure a step or a parameter.
//
// The default steps, in order, on every tracked frame after the fit from the prediction:
//  1. turned starts (turned_starts_step.h; where turn_start_deg > 0),
//  2. uncross the arms, 3. uncross the legs (uncross_step.h),
//  4. the front check after a start from the silhouette (front_check_step.h),
//  5. the front from the walking direction (travel_heading_step.h).

#include "capture-client/tracker/body_calibration.h"
#include "capture-client/tracker/body_fitter.h"
#include "capture-client/tracker/body_measurement.h"
#include "capture-client/tracker/body_start.h"
#include "capture-client/tracker/correction_step.h"
#include "capture-client/tracker/head_size.h"
#include "capture-client/tracker/joint_confidence.h"
#include "capture-client/tracker/person_detector.h"
#include "capture-client/tracker/skeleton_tracker_options.h"
#include "capture-client/tracker/static_scene_voxels.h"

namespace reenact::capture {

struct TrackerMethod {
  PersonDetectOptions detect;
  CalibrationOptions calibration;
  HeadSizeOptions head_size;  // the neck's depth measured while waiting for the calibration pose
  BodyFitterOptions fitter;
  BodyStartOptions start;
  BodyMeasurementOptions measurement;
  StaticSceneOptions static_scene;
  JointConfidenceOptions confidence;
  CorrectionSteps steps;

  void Check() const;
};

// The modules' defaults with the options applied (sensor range, iterations, turned starts,
// static scene, recovery, confidence) and the default steps above.
TrackerMethod DefaultTrackerMethod(const SkeletonTrackerOptions& options);

}  // namespace reenact::capture
