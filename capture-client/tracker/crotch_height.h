#pragma once
// The crotch's height above the floor measured in one depth frame of a walking person, for a
// body started without the calibration pose: the proportional body gives every
// subject legs of average length for its height, and a subject with shorter legs is tracked
// with its hips too high (CesiumMan's crotch is at 0.41 H, the procedural body's at 0.46 H).
//
// Method: from the floor under the midpoint of the two ankles (the tracked skeleton's), a
// vertical line is followed upwards in steps of step_m. Each sample projects to a pixel of the
// person's grid. Below the crotch, with the legs apart in the image, the samples see through
// the gap between the legs; the first sample whose pixel is the person's and whose depth
// reading lies within depth_tolerance_m of the sample's own depth is the crotch. A first
// person pixel much nearer than the sample (a leg in front of the gap: the legs apart along
// the line of sight), a gap lower than min_gap_m (legs together), or no hit below max_height_m
// gives no measurement.

#include <Eigen/Core>
#include <optional>

#include "capture-client/tracker/person_detector.h"
#include "common/geometry/pinhole_camera.h"

namespace reenact::capture {

struct CrotchHeightOptions {
  double step_m = 0.005;            // > 0
  double depth_tolerance_m = 0.15;  // > 0
  double min_gap_m = 0.25;          // the crotch at least this high above the floor, >= 0
  double max_height_m = 1.2;        // > min_gap_m

  void Check() const;
};

// blob: the frame's person (its grid on `camera`); ankles in the sensor frame.
std::optional<double> MeasureCrotchHeight(const PersonBlob& blob, const PinholeCamera& camera,
                                          const Eigen::Vector3d& left_ankle,
                                          const Eigen::Vector3d& right_ankle,
                                          const CrotchHeightOptions& options = {});

}  // namespace reenact::capture
