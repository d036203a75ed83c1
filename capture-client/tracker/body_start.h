#pragma once
// Starting a track on a frame without a tracked pose: a start without the calibration pose and
// the recovery of a lost track.
//  - From the calibration pose, when the blob shows it again (body_calibration.h's test): the
//    body placed arms out at the blob, fitted locally.
//  - From the silhouette: the body placed upright on the blob (the waist above the floor under
//    the blob's centroid, arms and legs straight down), facing each of heading_candidates
//    headings (heading.h: evenly spaced about up, the first facing the sensor) and the last
//    tracked heading; with extremities (a lost track's recovery), the same starts with the
//    limbs re-posed to reach the region's geodesic extremities (hands and feet,
//    geodesic_extremities.h and extremity_pose.h: a raised arm, arms out). Each start is fitted
//    from afar (BodyFitter::FitFromFar); the cheapest fit is taken when it is good. A start
//    without the calibration pose tries the upright starts only: on the bvh: walk seen from
//    the side at 4 m, the extremity starts won with poses that tracked worse.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "capture-client/tracker/body_calibration.h"
#include "capture-client/tracker/body_fitter.h"
#include "capture-client/tracker/correction_step.h"
#include "capture-client/tracker/geodesic_extremities.h"
#include "capture-client/tracker/person_detector.h"

namespace reenact::capture {

struct BodyStartOptions {
  int heading_candidates = 8;   // >= 1
  bool from_silhouette = true;  // else only the calibration pose starts a track again
  bool from_extremities = true;
  GeodesicExtremityOptions extremities;
  // A limb is re-posed to its extremity only when the upright start's limb end lies farther
  // than this from it (metres, >= 0; extremity_pose.h's min_offset_m).
  double extremity_min_offset_m = 0.25;
  // A start facing away from the sensor wins only when it costs less than (1 - gain) times
  // the cheapest facing it, [0, 1): a person in front of a sensor faces it unless the data say
  // otherwise clearly. Measured on utd-mhad's 108 real sequences (Kinect v1 at 3 m): without
  // it 35 tracks faced the wrong way, at 0.3 3 (at 0.4 1, but then a synthetic back seen
  // first, walk-handheld, starts the wrong way round; it costs over 30 % less).
  double facing_sensor_gain = 0.3;
  // A body of average proportions takes its height from the person's top as the person shows
  // it then; one that started while the person sat or crouched is too short once it stands. It
  // starts again at the new height when the person's top stands more than restart_taller_m
  // above the fitted body's top (PosedTopHeight) on restart_taller_frames good frames in a
  // row (> 0, >= 1). A raised hand does not count: the fitted arm reaches it.
  double restart_taller_m = 0.15;
  int restart_taller_frames = 5;

  void Check() const;
};

// The cheapest fit of upright starts on the blob's floor facing each of `headings` and, given
// extremities, of the same starts with the limbs reaching them (*from_extremities: whether
// such a start won). A fit facing away from the sensor counts its cost over
// (1 - facing_sensor_gain) (BodyStartOptions). nullopt without a floor or headings.
std::optional<BodyFitResult> BestUprightFit(const BodyFitter& fitter, const PersonBlob& blob,
                                            const BodyObservation& obs,
                                            const std::vector<Eigen::Vector3d>& headings,
                                            const GeodesicExtremities* extremities,
                                            double extremity_min_offset_m,
                                            double facing_sensor_gain, bool* from_extremities);

// The posed body's top above the floor: the highest joint, the head's crown counted (its height
// above the head joint in the rest pose).
double PosedTopHeight(const ArticulatedBody& body, const Skeleton& posed, const Plane3& floor);

struct StartedFit {
  BodyFitResult fit;
  TrackStart start = TrackStart::kSilhouette;
  bool from_extremities = false;  // the start's limbs reached the geodesic extremities
};

// A good fit that starts a track (above), or nullopt. last_pose: the track's last pose, whose
// heading is tried too; with_extremities: the extremity starts too.
std::optional<StartedFit> StartTrack(const BodyFitter& fitter, const GoodFitCriteria& good,
                                     const PersonBlob& blob, const BodyObservation& obs,
                                     const CalibrationOptions& calibration,
                                     const BodyStartOptions& options,
                                     const std::optional<ArticulatedPose>& last_pose,
                                     bool with_extremities);

}  // namespace reenact::capture
