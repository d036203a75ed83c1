#pragma once
// Correction steps: what the tracker does to a tracked frame's fit after the local fit from its
// prediction. Each step proposes candidate fits from the current fit and the observation; the
// tracker judges them in order under the step's rule (fit_acceptance.h), each against the fit
// as it stands, and runs the steps in the order of the list (tracker_method.h builds the list).
//
// A frame's fit "as the track is fitted" from a start pose: the fit from the start
// (BodyFitter::Fit), then steps [0, k) of the list. Step k may ask for it (StepFrame::
// fit_as_track) to follow a rival track as the track itself is followed.

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "capture-client/tracker/body_fitter.h"
#include "capture-client/tracker/fit_acceptance.h"
#include "capture-client/tracker/person_detector.h"

namespace reenact::capture {

// How a track started: from the calibration pose (its heading known) or from the silhouette
// (a start without the calibration pose, a recovery: its heading a guess).
enum class TrackStart { kCalibrationPose, kSilhouette };

// A tracked frame as a step sees it. References live for the frame.
struct StepFrame {
  const BodyFitter& fitter;
  const GoodFitCriteria& good;
  const PersonBlob& blob;
  const BodyObservation& observation;
  const std::optional<Eigen::Isometry3d>& world_from_sensor;
  // This fit's start: the track's last pose moved on by root_step (sensor frame, metres; zero
  // after a start), the prediction.
  ArticulatedPose prediction;
  Eigen::Vector3d root_step = Eigen::Vector3d::Zero();
  // The track's fit from `start` on this frame (see above).
  std::function<BodyFitResult(const ArticulatedPose& start)> fit_as_track;

  // `pose` moved on as the prediction is.
  ArticulatedPose Predicted(ArticulatedPose pose) const;
  // The shared rule's context with `input` as the step's input fit.
  AcceptanceContext Context(const BodyFitResult& input) const;
};

struct Candidate {
  BodyFitResult fit;
  // Judged by the step itself over several frames (the front check's rival): taken as it is.
  bool judged = false;
};

class CorrectionStep {
 public:
  virtual ~CorrectionStep() = default;
  virtual std::string_view name() const = 0;
  virtual AcceptanceRule rule() const = 0;
  // Before the fit from frame.prediction: a step may start fits of its own here, on threads of
  // its own, to be collected in Propose.
  virtual void Prepare(const StepFrame& /*frame*/) {}
  virtual std::vector<Candidate> Propose(const StepFrame& frame, const BodyFitResult& current) = 0;
  // A new track starts; a step drops what it held for the last one.
  virtual void OnTrackStart(TrackStart /*start*/) {}
  // A new subject (SkeletonTracker::Reset).
  virtual void Reset() {}
};

using CorrectionSteps = std::vector<std::unique_ptr<CorrectionStep>>;

// The fit as the track is fitted (above) from frame.prediction through steps [0, end); the
// frame's prediction, root_step and references are used, its fit_as_track is set per step.
BodyFitResult FitAsTrack(const CorrectionSteps& steps, size_t end, const StepFrame& frame);

}  // namespace reenact::capture
